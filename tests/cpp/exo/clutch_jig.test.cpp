// The clutch (section 4.4), the device over the gait cycle, the walking trials' failure
// (chapter 5), the ideal spring (figure 4.7), the tensile jig (appendix G.4, table 4.2) and the
// muscle as a static spring.

#include <algorithm>
#include <cmath>
#include <vector>

#include "approx.hpp"
#include "pamkit/exo/device.hpp"
#include "pamkit/exo/jig.hpp"
#include "pamkit/exo/spring.hpp"
#include "pamkit/muscle/free_inflation.hpp"

using namespace pamkit;
using namespace pamkit::exo;

namespace {
GaitCycle winter(std::size_t points = 690) {
  const GaitData data = winter_appendix_g3();
  return resample_cycle(data, detect_gait_events(data), points, 86.0);
}
bool never(const std::optional<double>& event) { return !event.has_value(); }
}  // namespace

TEST_CASE("the clutch: switching needs the full travel, and turning back undoes it", "[exo][clutch]") {
  ClutchParams p;  // engage 111, release 138, travel 7 (G.3, section 4.4)
  Clutch clutch(p, ClutchMode::engaged);
  CHECK(clutch.step(120.0) == ClutchMode::engaged);
  CHECK(clutch.step(115.0) == ClutchMode::engaged);
  CHECK(clutch.stretch_deg(115.0) == 5.0);           // the ratchet holds the bar at 120 deg
  CHECK(clutch.step(125.0) == ClutchMode::engaged);  // plantarflexion slips the ratchet
  CHECK(clutch.reference_deg() == 125.0);
  CHECK(clutch.step(140.0) == ClutchMode::releasing);
  CHECK(clutch.step(137.0) == ClutchMode::engaged);  // turned back before 145: the pawl spring re-seats it
  CHECK(clutch.step(144.9) == ClutchMode::releasing);
  CHECK(clutch.step(145.0) == ClutchMode::disengaged);
  CHECK(clutch.stretch_deg(100.0) == 0.0);
  CHECK(clutch.step(110.0) == ClutchMode::engaging);
  CHECK(clutch.step(112.0) == ClutchMode::disengaged);
  CHECK(clutch.step(104.0) == ClutchMode::engaged);
  CHECK(clutch.reference_deg() == 104.0);
  p.release_angle_deg = 100.0;
  CHECK_THROWS_WITH(Clutch(p), Catch::Contains("release_angle_deg"));
}

TEST_CASE("play is a dead zone: the device's range is the leg's less the play", "[exo][clutch]") {
  const GaitCycle cycle = winter();
  const auto [lo, hi] = std::minmax_element(cycle.ankle_angle_deg.begin(), cycle.ankle_angle_deg.end());
  PlayParams play;
  play.dead_zone_deg = 8.0;
  const DeviceRun run = run_device(cycle, Linkage{LinkageParams{}}, fit_clutch(cycle), play, LinearSpring{}, 3);
  const auto [dlo, dhi] = std::minmax_element(run.device_angle_deg.begin(), run.device_angle_deg.end());
  CHECK_REL(*dhi - *dlo, (*hi - *lo) - 8.0, 1e-9);
}

TEST_CASE("a well-fitted device engages before heel strike and releases after toe-off", "[exo][clutch]") {
  const GaitCycle cycle = winter();
  const ClutchParams screws = fit_clutch(cycle);
  const DeviceRun run = run_device(cycle, Linkage{LinkageParams{}}, screws, PlayParams{}, LinearSpring{}, 3);
  REQUIRE(run.engage_percent);
  REQUIRE(run.release_percent);
  // Figure 4.12 A: engaged in late swing, so it holds at heel contact (0 %).
  CHECK(*run.engage_percent > cycle.toe_off_percent);
  CHECK(run.mode.front() == static_cast<int>(ClutchMode::engaged));
  // Figure 4.12 C: released at push-off, after toe-off and by the most plantarflexed angle.
  const auto most =
      std::max_element(cycle.ankle_angle_deg.begin(), cycle.ankle_angle_deg.end()) - cycle.ankle_angle_deg.begin();
  CHECK(*run.release_percent >= cycle.toe_off_percent);
  CHECK(*run.release_percent <= cycle.percent[static_cast<std::size_t>(most)]);
  // It releases at the first sample past release screw + travel (the 7 deg of section 4.4).
  std::size_t first = 0;
  while (cycle.ankle_angle_deg[first] < screws.release_angle_deg + screws.switching_travel_deg) ++first;
  CHECK(*run.release_percent == cycle.percent[first]);
  // While switching the mechanism carries no torque (section 5.4.1), and it carries none in swing.
  for (std::size_t k = 0; k < run.mode.size(); ++k) {
    if (run.mode[k] != static_cast<int>(ClutchMode::engaged)) CHECK(run.torque_Nm[k] == 0.0);
  }
}

TEST_CASE("chapter 5: with the trials' ankle range and play the clutch never releases", "[exo][clutch]") {
  const GaitCycle normal = winter();
  const ClutchParams screws = fit_clutch(normal);  // set for the normal gait
  const Linkage linkage{LinkageParams{}};
  // Figure 5.4: the ankle's range fell to 15 deg with the device on. Figure 5.5: the muscle
  // stretched no more than 2 cm. With a perpendicular arm of about 15.5 cm that is about
  // 7.4 deg of device rotation, so the play took about 8 deg of the 15 (the value chosen here).
  const GaitCycle trial = with_ankle_range(normal, 15.0);
  PlayParams play;
  play.dead_zone_deg = 8.0;
  const DeviceRun run = run_device(trial, linkage, screws, play, LinearSpring{}, 3);
  CHECK(never(run.release_percent));
  CHECK(never(run.engage_percent));
  CHECK(
      std::all_of(run.mode.begin(), run.mode.end(), [](int m) { return m == static_cast<int>(ClutchMode::engaged); }));
  const double stretch = *std::max_element(run.elongation_m.begin(), run.elongation_m.end());
  CHECK_REL(stretch, linkage.elongation(linkage.params().block_angle_deg + 15.0 - 8.0),
            1e-9);  // engaged over the 7 deg
  CHECK(stretch <= 0.02);
  // Play alone does it too, if it eats the release travel: the full range less 16 deg of play
  // peaks below release screw + travel.
  PlayParams loose;
  loose.dead_zone_deg = 16.0;
  CHECK(never(run_device(normal, linkage, screws, loose, LinearSpring{}, 3).release_percent));
  // And so do G.3's own screws on Winter's gait: releasing needs 138 + 7 = 145 deg, the gait
  // peaks at 140.1 deg (row 49/50: 37.6 - 77.5 + 180).
  CHECK(never(run_device(normal, linkage, ClutchParams{}, PlayParams{}, LinearSpring{}, 3).release_percent));
}

TEST_CASE("compliance: the straps give by c x torque, and the spring stretches less", "[exo][clutch]") {
  const GaitCycle cycle = winter();
  const Linkage linkage{LinkageParams{}};
  const ClutchParams screws = fit_clutch(cycle);
  const LinearSpring spring{6000.0};
  const DeviceRun rigid = run_device(cycle, linkage, screws, PlayParams{}, spring, 3);
  PlayParams play;
  play.compliance_deg_per_Nm = 0.1;
  const DeviceRun soft = run_device(cycle, linkage, screws, play, spring, 3);
  const auto k =
      static_cast<std::size_t>(std::max_element(soft.torque_Nm.begin(), soft.torque_Nm.end()) - soft.torque_Nm.begin());
  CHECK_REL(soft.device_angle_deg[k] - soft.ankle_angle_deg[k], 0.1 * soft.torque_Nm[k], 1e-6);
  CHECK(*std::max_element(soft.elongation_m.begin(), soft.elongation_m.end()) <
        *std::max_element(rigid.elongation_m.begin(), rigid.elongation_m.end()));
}

TEST_CASE("the ideal spring inverts the forward model", "[exo][ideal]") {
  const GaitCycle cycle = winter();
  const Linkage linkage{LinkageParams{}};
  const DeviceRun run = run_device(cycle, linkage, fit_clutch(cycle), PlayParams{}, LinearSpring{}, 3);
  const IdealSpring ideal = ideal_spring(run, cycle.toe_off_percent, 0.25);
  // Driving the device with the ideal spring itself (force against elongation on its
  // stretching branch) gives back 25 % of the biological moment there.
  std::vector<double> e(ideal.elongation_m.begin(),
                        ideal.elongation_m.begin() + static_cast<long>(ideal.loading_samples));
  std::vector<double> f(ideal.force_N.begin(), ideal.force_N.begin() + static_cast<long>(ideal.loading_samples));
  auto law = [&](double x) {
    for (std::size_t i = 1; i < e.size(); ++i) {
      if (x <= e[i] && e[i] > e[i - 1]) return f[i - 1] + (f[i] - f[i - 1]) * (x - e[i - 1]) / (e[i] - e[i - 1]);
    }
    return f.back();
  };
  const DeviceRun back = run_device(cycle, linkage, fit_clutch(cycle), PlayParams{}, law, 3);
  int checked = 0;
  for (std::size_t k = 0; k < back.percent.size(); ++k) {
    if (back.percent[k] == ideal.percent[ideal.loading_samples / 2]) {
      CHECK_REL(back.torque_Nm[k], 0.25 * back.biological_torque_Nm[k], 1e-9);
      ++checked;
    }
  }
  CHECK(checked == 1);
  CHECK_THROWS_AS(ideal_spring(run, cycle.toe_off_percent, 0.0), InvalidInput);
}

TEST_CASE("jig conversion (G.4) agrees with the forward linkage on the same geometry", "[exo][jig]") {
  const LinkageParams linkage_params;
  const Linkage linkage(linkage_params);
  for (const Table42Row& row : table_4_2()) {
    JigParams jp;
    jp.initial_angle_deg = row.angle_deg;
    const Jig jig(linkage_params, jp);
    const JigSample start = jig.convert(0.0, 0.0);
    const JigSample end = jig.convert(row.vertical_displacement_m, 300.0);
    // Same triangle: the jig's theta is the linkage's heel-bar angle.
    CHECK_REL(start.muscle_length_m, linkage.pose(row.angle_deg).spring_length_m, 1e-12);
    CHECK_REL(end.muscle_length_m, linkage.pose(end.heel_bar_angle_deg).spring_length_m, 1e-12);
    CHECK_REL(end.heel_bar_angle_deg,
              row.angle_deg + std::asin(row.vertical_displacement_m / 0.3) * 180.0 / 3.14159265358979323846, 1e-12);
    // The moment the muscle puts on the heel bar is its force times the linkage's arm...
    CHECK_REL(end.ankle_moment_Nm, end.muscle_force_N * linkage.pose(end.heel_bar_angle_deg).moment_arm_m, 1e-9);
    // ...and the moment balance of the shank (figure 4.17) makes it the crosshead force times
    // the horizontal distance of A (G.4's commented-out "Moment = A(i,3) * 0.3" is this with 0.3 m).
    const double beta = (95.0 - end.heel_bar_angle_deg) * 3.14159265358979323846 / 180.0;
    const double ax = 0.3 * std::cos(beta) - 0.1 * std::sin(beta);
    CHECK_REL(end.ankle_moment_Nm, 300.0 * ax, 1e-9);
    // Table 4.2's lengths were measured, end caps included; the geometry gives them within 2.6 %.
    CHECK_REL(start.muscle_length_m, row.muscle_length_m, 0.026);
  }
  // Section 4.6.2: 15 deg of rotation moves the free end about 8 cm (0.3 sin 15 deg = 7.8 cm).
  const JigSample fifteen =
      Jig(linkage_params, JigParams{}).convert(0.3 * std::sin(15.0 * 3.14159265358979323846 / 180.0), 0.0);
  CHECK_REL(fifteen.rotation_deg, 15.0, 1e-12);
  CHECK_THROWS_WITH(Jig(linkage_params, JigParams{}).convert(0.31, 0.0), Catch::Contains("upright_length_m"));
  JigParams bad;
  bad.initial_angle_deg = 0.0;
  CHECK_THROWS_WITH(Jig(linkage_params, bad), Catch::Contains("initial_angle_deg"));
}

TEST_CASE("the muscle as a static spring: zero force at its free length, Boyle's law", "[exo][spring]") {
  const MuscleBuild build;
  const GasParams gas;
  const FreeInflation free =
      free_inflation(BraidGeometry(build), BladderLaw::thesis(), gas.atmospheric_pressure_Pa, 70e3);
  const PamStaticSpring pam(build, BladderLaw::thesis(), gas, free.length_m, 70e3);
  CHECK(std::abs(pam(0.0)) < 1e-6);  // free_inflation's length is where the force is zero
  const BraidGeometry geometry(build);
  const double v0 = geometry.shape(free.length_m).gas_volume;
  const double v = geometry.shape(free.length_m + 0.03).gas_volume;
  CHECK_REL(pam.gauge_pressure(0.03) + gas.atmospheric_pressure_Pa, (70e3 + gas.atmospheric_pressure_Pa) * v0 / v,
            1e-12);
  CHECK(pam(0.03) > pam(0.02));
  CHECK_THROWS_AS(pam(1.0), InvalidInput);  // beyond the braid
}

TEST_CASE("walking trajectory: strides of the device's elongation", "[exo][walking]") {
  const GaitCycle cycle = winter(100);
  const DeviceRun run = run_device(cycle, Linkage{LinkageParams{}}, fit_clutch(cycle), PlayParams{}, LinearSpring{}, 3);
  const ElongationTrajectory t = walking_trajectory(run, 1.2, 4, 0.005);
  REQUIRE(t.size() == 4 * 100 + 1);
  CHECK_REL(t.time().back(), 4.8, 1e-12);
  CHECK_REL(t.elongation()[150], run.elongation_m[50] + 0.005, 1e-12);
  CHECK_THROWS_AS(walking_trajectory(run, 0.0, 4), InvalidInput);
}
