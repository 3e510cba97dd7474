// Gait data, linkage and appendix G.3's script: chapter 4's kinematics (section 4.3).

#include <algorithm>
#include <cmath>
#include <string>

#include "approx.hpp"
#include "pamkit/exo/device.hpp"

using namespace pamkit;
using namespace pamkit::exo;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Spring length of the G.3 geometry written out by hand (law of cosines in the shank frame).
double hand_length(const LinkageParams& p, double psi_deg) {
  return std::hypot(p.upright_length_m - p.heel_offset_m * std::cos(psi_deg * kDeg),
                    p.shank_offset_m - p.heel_offset_m * std::sin(psi_deg * kDeg));
}
}  // namespace

TEST_CASE("Winter's table as printed in G.3 and its gait events", "[exo][gait]") {
  const GaitData data = winter_appendix_g3();
  REQUIRE(data.size() == 84);                  // G.3 declares zeros(1,84)
  CHECK(data.leg_deg()[0] == 107.8);           // first value of legangleraw
  CHECK(data.ankle_moment_Nm()[35] == -89.8);  // the stance peak of anklemomentraw
  const GaitEvents events = detect_gait_events(data);
  // By eye from the printed moment: it turns dorsiflexor at frame 4 (-1.7 -> 4.6) and the
  // plantarflexor moment ends at frame 45 (-3.6 -> 1.4).
  CHECK(events.heel_strike_frame == 4.0);
  CHECK(events.toe_off_frame == 45.0);
  // The stride: no other lag between 60 and 75 frames repeats the angles as well.
  auto rms = [&](int lag) {
    double sum = 0.0;
    for (std::size_t i = 0; i + static_cast<std::size_t>(lag) < data.size(); ++i) {
      const auto j = i + static_cast<std::size_t>(lag);
      sum += std::pow(data.hip_deg()[j] - data.hip_deg()[i], 2) + std::pow(data.leg_deg()[j] - data.leg_deg()[i], 2) +
             std::pow(data.foot_deg()[j] - data.foot_deg()[i], 2);
    }
    return std::sqrt(sum / static_cast<double>(data.size() - static_cast<std::size_t>(lag)));
  };
  for (int lag = 60; lag <= 75; ++lag) {
    if (lag != static_cast<int>(events.stride_frames)) CHECK(rms(lag) > rms(static_cast<int>(events.stride_frames)));
  }

  const GaitCycle cycle = resample_cycle(data, events, 138, 86.0);
  CHECK(cycle.leg_deg[0] == data.leg_deg()[3]);              // 0 % is frame 4
  CHECK_REL(cycle.leg_deg[2], data.leg_deg()[4], 1e-12);     // 2 samples per frame: 1.45 % is frame 5
  CHECK_REL(cycle.moment_Nm[2], -8.3 * 86.0 / 56.7, 1e-12);  // frame 5's 8.3 N m, sign flipped, scaled to 86 kg
  CHECK_REL(cycle.ankle_angle_deg[0], 110.7 - 175.5 + 180.0, 1e-12);  // G.3 testangle at frame 4
  CHECK_THROWS_AS(resample_cycle(data, GaitEvents{20.0, 60.0, 69.0}, 100, 86.0), InvalidInput);  // runs past frame 84
}

TEST_CASE("bad gait input is named", "[exo][gait]") {
  CHECK_THROWS_WITH(GaitData({1, 2, 3}, {0, 0, 0}, {0, 0}, {0, 0, 0}, {0, 0, 0}), Catch::Contains("leg_deg"));
  CHECK_THROWS_WITH(GaitData({1, 2, 4}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}), Catch::Contains("frame[2]"));
}

TEST_CASE("linkage: spring length by hand, moment arm = dL/dpsi (virtual work)", "[exo][linkage]") {
  const LinkageParams p;  // G.3: 0.30 m, 0.10 m, 0.17 m, 100 deg
  const Linkage linkage(p);
  CHECK_REL(linkage.min_spring_length(), hand_length(p, 100.0), 1e-14);
  for (double psi = 60.0; psi <= 150.0; psi += 10.0) {
    const double h = 1e-4;
    const double derivative = (hand_length(p, psi + h) - hand_length(p, psi - h)) / (2.0 * h * kDeg);
    CHECK_REL(linkage.pose(psi).moment_arm_m, derivative, 1e-7);
    CHECK_REL(linkage.pose(psi).spring_length_m, hand_length(p, psi), 1e-14);
  }
}

TEST_CASE("geometry that cannot work is rejected with the field's name", "[exo][linkage]") {
  LinkageParams p;
  p.block_angle_deg = 200.0;
  CHECK_THROWS_WITH(Linkage(p), Catch::Contains("block_angle_deg"));
  p = LinkageParams{};
  p.block_angle_deg = 10.0;  // the spring's line passes in front of the ankle: tension would dorsiflex
  CHECK_THROWS_WITH(Linkage(p), Catch::Contains("block_angle_deg") && Catch::Contains("in front of the ankle"));
  p = LinkageParams{};
  p.heel_offset_m = -0.17;
  CHECK_THROWS_WITH(Linkage(p), Catch::Contains("heel_offset_m"));
  p = LinkageParams{};
  p.shank_offset_m = 0.30 * std::sin(1.0 * kDeg);
  p.heel_offset_m = 0.30;
  p.block_angle_deg = 1.0;  // the heel anchor lands on the shank anchor: the spring cannot close
  CHECK_THROWS_WITH(Linkage(p), Catch::Contains("cannot close"));
}

TEST_CASE("the lab-frame script and the shank-frame linkage agree", "[exo][linkage]") {
  // G.3 computes points in the lab: knee from the hip, ankle from the knee, the anchors from
  // those. Redo it for a few rows and compare with the shank-frame linkage.
  const GaitData data = winter_appendix_g3();
  const Linkage linkage{LinkageParams{}};
  const ScriptKinematics script = reproduce_g3_script(data, linkage, 56.7);
  const double pi = 3.14159265358979323846;
  const double fha = (data.foot_deg()[11] * kDeg + pi) - (data.leg_deg()[11] * kDeg + pi - pi + 100.0 * kDeg);
  for (std::size_t row : {5u, 20u, 35u, 41u, 60u}) {  // 1-based rows
    const std::size_t i = row - 1;
    const double hip = data.hip_deg()[i] * kDeg + pi, leg = data.leg_deg()[i] * kDeg + pi,
                 foot = data.foot_deg()[i] * kDeg + pi;
    const double kx = 500.0 + row / 20.0 + std::cos(hip) * 0.42, ky = 500.0 + std::sin(hip) * 0.42;
    const double ax = kx + std::cos(leg) * 0.425, ay = ky + std::sin(leg) * 0.425;
    const double ux = kx + std::cos(leg) * (0.425 - 0.3), uy = ky + std::sin(leg) * (0.425 - 0.3);
    const double sx = ux + std::cos(leg - pi / 2) * 0.1, sy = uy + std::sin(leg - pi / 2) * 0.1;
    const bool engaged = row > 12 && row < 43;
    const double heel = engaged ? foot - fha : leg - pi + 100.0 * kDeg;
    const double hx = ax + std::cos(heel) * 0.17, hy = ay + std::sin(heel) * 0.17;
    const double length = std::hypot(hx - sx, hy - sy);
    const double arm = ((sx - hx) / length) * (hy - ay) + ((sy - hy) / length) * (ax - hx);
    CHECK_REL(script.spring_length_m[row - 2], length, 1e-9);
    CHECK_REL(script.moment_arm_m[row - 2], arm, 1e-9);
    CHECK_REL(script.horizontal_lever_m[row - 2], ax - hx, 1e-9);
  }
}

TEST_CASE("chapter 4 kinematics: appendix G.3's parameters and the text's figures", "[exo][chapter4]") {
  const GaitData data = winter_appendix_g3();
  // Heel bar turned off the block by the ankle angle at row 12 (beginstretch) less the most
  // dorsiflexed angle of rows 13-42, both read from the printed table.
  double most = 1e9;
  for (std::size_t i = 12; i <= 41; ++i) most = std::min(most, data.ankle_angle_deg(i));
  const double stretch_deg = data.ankle_angle_deg(11) - most;
  CHECK_REL(stretch_deg, (95.9 - 151.9) - (68.7 - 139.2), 1e-12);  // rows 12 and 35: 124.0 - 109.5 deg

  SECTION("G.3 as printed (block 100 deg): the spring spans 33.6-37.5 cm, not 25-30") {
    const LinkageParams p;
    const ScriptKinematics s = reproduce_g3_script(data, Linkage(p), 86.0);
    const auto [lmin, lmax] = std::minmax_element(s.spring_length_m.begin(), s.spring_length_m.end());
    CHECK_REL(*lmin, hand_length(p, 100.0), 1e-12);
    CHECK_REL(*lmax, hand_length(p, 100.0 + stretch_deg), 1e-12);
    const double emax = *std::max_element(s.elongation_m.begin(), s.elongation_m.end());
    CHECK_REL(emax, hand_length(p, 100.0 + stretch_deg) - hand_length(p, 100.0), 1e-12);
    // What the code reaches against the text (figure 4.5): 0.336-0.375 m vs 0.25-0.30 m, and
    // 3.82 cm vs 4.25 cm: not within 10 % (docs/exo.md: not all of the text's figures follow from G.3).
    CHECK(*lmin > 0.25 * 1.30);
    CHECK(emax < 0.0425 * 0.91);
    // Figure 4.7, 86 kg: ~1000 N near 4 cm. The ideal force peaks at row 35 (-89.7 N m for
    // 56.7 kg, where the arm is shortest; row 36's -89.8 N m meets a longer arm) and reaches
    // 953 N: within 5 %.
    const double peak = *std::max_element(s.ideal_force_N.begin(), s.ideal_force_N.end());
    CHECK_REL(
        peak,
        89.7 * 86.0 / 56.7 / Linkage(p).pose(100.0 + data.ankle_angle_deg(11) - data.ankle_angle_deg(34)).moment_arm_m,
        1e-12);
    CHECK_REL(peak, 1000.0, 0.05);
  }
  SECTION("block angle 70 deg reproduces figures 4.4 and 4.5 within 10 %") {
    LinkageParams p;
    p.block_angle_deg = 70.0;
    const ScriptKinematics s = reproduce_g3_script(data, Linkage(p), 86.0);
    const auto [lmin, lmax] = std::minmax_element(s.spring_length_m.begin(), s.spring_length_m.end());
    CHECK_REL(*lmin, 0.25, 0.10);  // figure 4.5 A: "approximately between 25 and 30 cm"
    CHECK_REL(*lmax, 0.30, 0.10);
    CHECK_REL(*std::max_element(s.elongation_m.begin(), s.elongation_m.end()), 0.0425, 0.10);  // figure 4.5 B
    // Figure 4.4's "between 5 and 17 cm" is the horizontal lever (G.3's momentarm(1,:)); the
    // perpendicular arm stays within 16.8-17.0 cm.
    const auto [hmin, hmax] = std::minmax_element(s.horizontal_lever_m.begin(), s.horizontal_lever_m.end());
    CHECK_REL(*hmin, 0.05, 0.10);
    CHECK_REL(*hmax, 0.17, 0.10);
    const auto [amin, amax] = std::minmax_element(s.moment_arm_m.begin(), s.moment_arm_m.end());
    CHECK(*amin > 0.16);
    CHECK(*amax <= p.heel_offset_m);
  }
}
