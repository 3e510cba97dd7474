// What a commercial muscle needs beyond the thesis's: a neo-Hookean membrane, a braid angle as a
// datasheet gives it, and a braid that goes slack instead of pushing. Each against a closed form
// or an invariant.

#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "pamkit/effects/catalog.hpp"
#include "pamkit/effects/pipeline.hpp"
#include "pamkit/muscle/free_inflation.hpp"

namespace {

using namespace pamkit;

constexpr double kPi = 3.14159265358979323846;
constexpr double kAtmosphere = 101e3;
constexpr double kShearModulus = 1.2e6;  // a soft natural rubber [Pa]
const FrictionParams kNoFriction{0.0, 0.0, 0.0, 0.0, 0.0};

// Strain energy per unit deflated volume of the incompressible neo-Hookean membrane.
double neo_hookean_energy(double eps_l, double eps_h) {
  const double ll = 1.0 + eps_l;
  const double lh = 1.0 + eps_h;
  return 0.5 * kShearModulus * (ll * ll + lh * lh + 1.0 / (ll * ll * lh * lh) - 3.0);
}

// A Festo-like build: 10 mm, 250 mm, flat press-fitted ends, a pre-stretched membrane.
MuscleBuild commercial_build() {
  MuscleBuild b;
  b.length_m = 0.250;
  b.diameter_m = 0.010;
  b.bladder_diameter_m = 0.0097;
  b.bladder_thickness_m = 0.5e-3;
  b.fiber_thickness_m = 0.0;
  b.end_diameter_m = 0.005;
  b.cone_generator_m = 0.0;
  b.fiber_revolutions = fiber_revolutions_for_braid_angle(b, 21.0);
  return b;
}

}  // namespace

TEST_CASE("A neo-Hookean membrane in uniaxial tension has P = mu (lambda - lambda^-2) and no lateral stress",
          "[membrane]") {
  // Closed form of the incompressible neo-Hookean solid in uniaxial tension: lateral stretch
  // lambda^-1/2, nominal stress mu (lambda - 1/lambda^2), lateral stress zero.
  const BladderLaw law = BladderLaw::neo_hookean(kShearModulus);
  for (double stretch : {0.8, 1.0, 1.3, 2.0}) {
    INFO("lambda = " << stretch);
    const BiaxialStress s = law.stresses(stretch - 1.0, 1.0 / std::sqrt(stretch) - 1.0);
    CHECK(std::abs(s.longitudinal - kShearModulus * (stretch - 1.0 / (stretch * stretch))) <= 1e-9 * kShearModulus);
    CHECK(std::abs(s.hoop) <= 1e-9 * kShearModulus);
  }
}

TEST_CASE("The neo-Hookean stresses and tangent moduli are the derivatives of its strain energy", "[membrane]") {
  const BladderLaw law = BladderLaw::neo_hookean(kShearModulus);
  const double h = 1e-6;  // central differences: error ~h^2 of the second derivative
  for (double eps_l : {-0.2, 0.0, 0.15}) {
    for (double eps_h : {0.0, 0.3, 0.8}) {
      INFO("eps_l = " << eps_l << ", eps_h = " << eps_h);
      const BiaxialStress s = law.stresses(eps_l, eps_h);
      const BiaxialStress k = law.tangent_moduli(eps_l, eps_h);
      CHECK_REL(s.longitudinal + 1.0,
                (neo_hookean_energy(eps_l + h, eps_h) - neo_hookean_energy(eps_l - h, eps_h)) / (2 * h) + 1.0, 1e-6);
      CHECK_REL(s.hoop + 1.0,
                (neo_hookean_energy(eps_l, eps_h + h) - neo_hookean_energy(eps_l, eps_h - h)) / (2 * h) + 1.0, 1e-6);
      CHECK_REL(k.longitudinal,
                (law.stresses(eps_l + h, eps_h).longitudinal - law.stresses(eps_l - h, eps_h).longitudinal) / (2 * h),
                1e-6);
      CHECK_REL(k.hoop, (law.stresses(eps_l, eps_h + h).hoop - law.stresses(eps_l, eps_h - h).hoop) / (2 * h), 1e-6);
    }
  }
  CHECK_THROWS_AS(BladderLaw::neo_hookean(-1.0), InvalidParameter);
}

TEST_CASE("The bladder force of a neo-Hookean membrane is the derivative of its stored energy", "[membrane][force]") {
  // Virtual work: F_bladder = dU/dL with U = V_rubber W(eps_l(L), eps_h(L)).
  const BraidGeometry geometry(commercial_build());
  const BladderLaw law = BladderLaw::neo_hookean(kShearModulus);
  const double volume = bladder_reference_volume(geometry);
  auto energy = [&](double L) {
    const BladderState b = bladder_state(geometry, geometry.shape(L), law);
    return volume * neo_hookean_energy(b.longitudinal_strain, b.hoop_strain);
  };
  const double h = 1e-7;
  for (double L : {0.19, 0.21, 0.23, 0.245}) {
    INFO("L = " << L);
    const double force =
        muscle_forces(geometry, geometry.shape(L), law, kNoFriction, kAtmosphere, kAtmosphere, 0.0).bladder;
    CHECK_REL(force, (energy(L + h) - energy(L - h)) / (2 * h), 1e-5);
  }
}

TEST_CASE("A braid angle converts to fiber revolutions through tan(theta) = pi n D / Lm", "[geometry]") {
  MuscleBuild build = commercial_build();
  for (double angle : {12.0, 21.0, 35.0}) {
    build.fiber_revolutions = fiber_revolutions_for_braid_angle(build, angle);
    // Flat ends: the cylinder is the whole deflated length.
    CHECK_REL(build.fiber_revolutions, build.length_m * std::tan(angle * kPi / 180.0) / (kPi * build.diameter_m),
              1e-12);
    CHECK_REL(deflated_braid_angle_deg(build), angle, 1e-12);
    // The geometry agrees: at the deflated length its braid angle is the datasheet's.
    CHECK_REL(BraidGeometry(build).shape(build.length_m * (1 - 1e-9)).braid_angle * 180.0 / kPi, angle, 1e-6);
  }
  MuscleBuild thesis;  // with end cones the cylinder is shorter than the muscle
  CHECK_REL(fiber_revolutions_for_braid_angle(thesis, deflated_braid_angle_deg(thesis)), thesis.fiber_revolutions,
            1e-12);
  CHECK_THROWS_AS(fiber_revolutions_for_braid_angle(build, 0.0), InvalidParameter);
  CHECK_THROWS_AS(fiber_revolutions_for_braid_angle(build, 90.0), InvalidParameter);
}

TEST_CASE("A slack braid transmits tension, nothing below zero, and joins the two smoothly", "[slack]") {
  const double band = 2.0;
  CHECK(braid_tension(-50.0, 0.0) == -50.0);  // band 0: the thesis's braid pushes
  CHECK(braid_tension(-50.0, band) == 0.0);
  CHECK(braid_tension(-band, band) == 0.0);
  CHECK(braid_tension(band, band) == band);
  CHECK(braid_tension(30.0, band) == 30.0);
  // C1 at both ends of the band: value and slope match (0 and 1, 0 and 0).
  const double h = 1e-7;
  CHECK(std::abs((braid_tension(band + h, band) - braid_tension(band - h, band)) / (2 * h) - 1.0) < 1e-6);
  CHECK(std::abs((braid_tension(-band + h, band) - braid_tension(-band - h, band)) / (2 * h)) < 1e-6);
  for (double f = -3.0; f < 3.0; f += 0.1) CHECK(braid_tension(f, band) >= std::max(f, 0.0));
}

TEST_CASE("Held below its free length a slack muscle carries nothing; above it, the elastic force", "[slack]") {
  // The onset is the free-inflation length: where the gas-and-bladder force crosses zero.
  MuscleParams params;
  params.build = commercial_build();
  params.bladder = BladderLaw::neo_hookean(kShearModulus);
  params.gas.atmospheric_pressure_Pa = kAtmosphere;
  const double band = 1.0;
  const EffectPtr slack = EffectCatalog::builtin().make("braid_slack");
  slack->set_value("band_N", band);
  const BraidGeometry geometry(params.build);
  for (double gauge_Pa : {150e3, 400e3}) {
    const double free = free_inflation(geometry, params.bladder, kAtmosphere, gauge_Pa).length_m;
    INFO("p = " << gauge_Pa << " Pa, free length " << free << " m");
    const std::vector<double> lengths{free - 0.02, free - 0.005, free + 0.005, free + 0.02};
    const std::vector<double> pressures(lengths.size(), gauge_Pa);
    const std::vector<double> pushing = static_forces(params, lengths, pressures);
    const std::vector<double> slackened = static_forces(params, lengths, pressures, {slack});
    REQUIRE(pushing[0] < -band);  // the thesis's braid pushes there
    CHECK(slackened[0] == 0.0);
    CHECK(slackened[1] == 0.0);
    CHECK(slackened[2] == pushing[2]);  // taut: the elastic force, unchanged
    CHECK(slackened[3] == pushing[3]);
    CHECK(pushing[3] > pushing[2]);
  }
}

TEST_CASE("static_forces is the supplied test's force at rest", "[slack][supplied]") {
  MuscleParams params;
  params.build = commercial_build();
  params.bladder = BladderLaw::neo_hookean(kShearModulus);
  const std::vector<double> time{0.0, 1.0, 2.0, 3.0};
  const std::vector<double> held(time.size(), 0.0);
  const std::vector<double> pressure{100e3, 250e3, 400e3, 550e3};
  const double length = 0.23;
  const Measurement m = simulate_supplied_measurement(params, length, ElongationTrajectory(time, held), pressure, {});
  const std::vector<double> forces = static_forces(params, std::vector<double>(time.size(), length), pressure);
  for (std::size_t k = 0; k < time.size(); ++k) CHECK(forces[k] == m.force_N[k]);
  CHECK_THROWS_AS(static_forces(params, {0.23}, {100e3, 200e3}), InvalidInput);
  CHECK_THROWS_AS(static_forces(params, {0.23}, {100e3}, {EffectCatalog::builtin().make("sensor_lag")}),
                  InvalidParameter);
}

TEST_CASE("An isotonic muscle settles where Gaylord's force equals its load", "[isotonic]") {
  // Thin walls, flat ends, no bladder: the force is -p dV/dL of a cylinder of inextensible
  // fibers, p pi D0^2 / (4 sin^2 theta0) (3 cos^2 theta - 1), so the length carrying a load F
  // at gauge p is L = Lf cos(theta) with cos^2 theta = (1 + 4 F sin^2 theta0 / (p pi D0^2)) / 3.
  MuscleParams params;
  params.build = commercial_build();
  params.build.bladder_thickness_m = 0.0;
  params.build.bladder_diameter_m = params.build.diameter_m;
  params.bladder = BladderLaw::none();
  const double theta0 = 21.0 * kPi / 180.0;
  const double fiber = params.build.length_m / std::cos(theta0);
  const double d0 = params.build.diameter_m;
  const double load = 80.0;
  const std::vector<double> pressures{200e3, 400e3, 600e3, 400e3, 200e3};
  const IsotonicLengths path = isotonic_lengths(params, pressures, load, params.build.length_m);
  for (std::size_t k = 0; k < pressures.size(); ++k) {
    INFO("p = " << pressures[k] << " Pa");
    const double p = pressures[k];
    const double cos2 = (1.0 + 4.0 * load * std::sin(theta0) * std::sin(theta0) / (p * kPi * d0 * d0)) / 3.0;
    CHECK_REL(path.length_m[k], fiber * std::sqrt(cos2), 1e-8);
    CHECK_FALSE(path.at_limit[k]);
  }
  // No hysteresis: the same pressure gives the same length on the way up and down.
  CHECK(path.length_m[1] == Approx(path.length_m[3]).epsilon(1e-10));
}

TEST_CASE("Pressurise/vent friction makes the muscle shorter on venting than on pressurising", "[isotonic]") {
  MuscleParams params;
  params.build = commercial_build();
  params.bladder = BladderLaw::neo_hookean(kShearModulus);
  const EffectPtr hysteresis = EffectCatalog::builtin().make("pressure_hysteresis");
  hysteresis->set_value("coefficient", 0.1);
  const std::vector<double> pressures{200e3, 400e3, 600e3, 400e3, 200e3};
  const std::vector<double> branch = pressure_branches(pressures);
  CHECK(branch == std::vector<double>{1.0, 1.0, 1.0, -1.0, -1.0});
  const IsotonicLengths path = isotonic_lengths(params, pressures, 100.0, params.build.length_m, {hysteresis});
  CHECK(path.length_m[3] < path.length_m[1]);
  CHECK(path.length_m[4] < path.length_m[0]);
  // At a held length the same friction shows as force: venting reads more than pressurising.
  const std::vector<double> held(pressures.size(), 0.23);
  const std::vector<double> force = static_forces(params, held, pressures, {hysteresis});
  const double pressure_force =
      0.1 * 400e3 * 0.25 * kPi * std::pow(BraidGeometry(params.build).shape(0.23).diameter, 2);
  CHECK_REL(force[3] - force[1], 2.0 * pressure_force, 1e-9);
  // Noise within the play (2 kPa) does not flip the branch.
  CHECK(pressure_branches({100e3, 101e3, 100.5e3, 101.5e3, 100.8e3}) == std::vector<double>(5, 1.0));
}

TEST_CASE("Free inflation is the isotonic solve with no load", "[isotonic][free_inflation]") {
  // Table 3.4's pressures on PAM 2: the muscle inflated with nothing on its ends settles where
  // the force is zero, whichever solve finds it.
  MuscleParams params;  // PAM 2, the thesis bladder
  const BraidGeometry geometry(params.build);
  const std::vector<double> pressures{138e3, 207e3, 276e3};
  const IsotonicLengths path = isotonic_lengths(params, pressures, 0.0, params.build.length_m);
  for (std::size_t k = 0; k < pressures.size(); ++k) {
    INFO("p = " << pressures[k] << " Pa");
    const double free =
        free_inflation(geometry, params.bladder, params.gas.atmospheric_pressure_Pa, pressures[k]).length_m;
    CHECK_REL(path.length_m[k], free, 1e-9);
  }
}

TEST_CASE("A transducer error in a supplied test acts on the pressure that drives the model",
          "[supplied][instruments]") {
  // The rig's transducer reads 0.96 p - 10 kPa. Given its readings, sensor_offset with those
  // numbers drives the model with the true pressures and reports the readings unchanged.
  MuscleParams params;
  params.build = commercial_build();
  params.bladder = BladderLaw::neo_hookean(kShearModulus);
  const EffectPtr transducer = EffectCatalog::builtin().make("sensor_offset");
  transducer->set_value("gain", 0.96);
  transducer->set_value("offset_Pa", -10e3);
  const std::vector<double> truth{150e3, 300e3, 450e3, 300e3};
  std::vector<double> reading;
  for (double p : truth) reading.push_back(0.96 * p - 10e3);
  const std::vector<double> time{0.0, 1.0, 2.0, 3.0};
  const ElongationTrajectory held(time, std::vector<double>(time.size(), 0.0));
  const Measurement m = simulate_supplied_measurement(params, 0.23, held, reading, {transducer});
  const Measurement exact = simulate_supplied_measurement(params, 0.23, held, truth, {});
  for (std::size_t k = 0; k < time.size(); ++k) {
    CHECK_REL(m.force_N[k], exact.force_N[k], 1e-12);
    CHECK_REL(m.gauge_pressure_Pa[k], reading[k], 1e-12);
  }
  const std::vector<double> lengths(truth.size(), 0.23);
  const std::vector<double> table = static_forces(params, lengths, reading, {transducer});
  for (std::size_t k = 0; k < time.size(); ++k) CHECK_REL(table[k], exact.force_N[k], 1e-12);
}

TEST_CASE("A hose's lag in a supplied test drives the muscle with the ramp's closed-form response", "[supplied]") {
  // The transducer reads a ramp a t at the regulator; through a hose of time constant tau the
  // muscle's pressure is a (t - tau (1 - exp(-t / tau))), the exact response of tau dy/dt = x - y
  // started settled. The force is the static force at that pressure (the muscle is held still),
  // and the reported pressure is the reading. Settled rows of a table see no lag.
  MuscleParams params;
  params.build = commercial_build();
  params.bladder = BladderLaw::neo_hookean(kShearModulus);
  const double slope = 100e3;  // Pa/s
  const double tau = 0.4;      // s
  const EffectPtr hose = EffectCatalog::builtin().parse("sensor_lag:channel=gauge_pressure_Pa,time_constant_s=0.4");
  REQUIRE(hose->reads_supplied_pressure());
  std::vector<double> time, reading, lagged;
  for (int k = 0; k <= 50; ++k) {
    const double t = 0.1 * k;
    time.push_back(t);
    reading.push_back(slope * t);
    lagged.push_back(slope * (t - tau * (1.0 - std::exp(-t / tau))));
  }
  const ElongationTrajectory held(time, std::vector<double>(time.size(), 0.0));
  const Measurement m = simulate_supplied_measurement(params, 0.23, held, reading, {hose});
  const Measurement exact = simulate_supplied_measurement(params, 0.23, held, lagged, {});
  for (std::size_t k = 0; k < time.size(); ++k) {
    CHECK(m.force_N[k] == Approx(exact.force_N[k]).epsilon(1e-9).margin(1e-9));
    CHECK(m.gauge_pressure_Pa[k] == reading[k]);
  }
  const std::vector<double> lengths(time.size(), 0.23);
  const std::vector<double> settled = static_forces(params, lengths, reading, {hose});
  const std::vector<double> without = static_forces(params, lengths, reading, {});
  for (std::size_t k = 0; k < time.size(); ++k) CHECK(settled[k] == without[k]);
  // On another channel the lag is the instrument's, not the drive's.
  CHECK_FALSE(EffectCatalog::builtin().parse("sensor_lag:channel=force_N")->reads_supplied_pressure());
}
