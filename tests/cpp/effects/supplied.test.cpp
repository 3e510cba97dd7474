// A supplied-pressure test (the muscle on a regulator: the measured pressure drives the static
// model) checked against the sealed simulation, which computes the same force by another path:
// fed the pressure the sealed gas reaches, the supplied model must give the sealed force.

#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "effect_test_support.hpp"

using namespace pamkit_test;

namespace {

/// Without friction the force depends on length and pressure alone, not on how the velocity
/// is sampled, so the two paths must agree to the integrator's tolerance.
MuscleParams frictionless() {
  MuscleParams params;
  params.friction.fiber_fiber_coefficient = 0.0;
  params.friction.fiber_bladder_coefficient = 0.0;
  return params;
}

ElongationTrajectory smooth_stretch() {
  std::vector<double> time, elongation;
  for (int k = 0; k <= 400; ++k) {
    time.push_back(0.05 * k);
    elongation.push_back(0.012 * std::sin(0.5 * time.back()) * std::sin(0.5 * time.back()));
  }
  return ElongationTrajectory(time, elongation);
}

}  // namespace

TEST_CASE("supplied: the sealed gas's pressure, supplied, gives the sealed force", "[effects][supplied]") {
  const MuscleParams params = frictionless();
  const ElongationTrajectory crosshead = smooth_stretch();
  const Measurement sealed = measure(params, table_c2_90(), crosshead, {});
  const Measurement supplied =
      simulate_supplied_measurement(params, table_c2_90().length_m, crosshead, sealed.gauge_pressure_Pa, {});
  REQUIRE(supplied.force_N.size() == sealed.force_N.size());
  for (std::size_t k = 0; k < sealed.force_N.size(); ++k) {
    INFO("sample " << k);
    // Both evaluate the same force at the same length and pressure; the pressure is the
    // sealed run's output (relative tolerance 1e-10), so they agree to about that.
    CHECK(supplied.force_N[k] == Approx(sealed.force_N[k]).epsilon(1e-8).margin(1e-8));
  }
  CHECK(supplied.gauge_pressure_Pa == sealed.gauge_pressure_Pa);  // the input, read back as measured
  for (double t : supplied.temperature_K) CHECK(t == params.gas.ambient_temperature_K);  // the regulator's gas
}

TEST_CASE("supplied: effects act at their stages, and a sealed-only effect is refused with its reason",
          "[effects][supplied]") {
  const MuscleParams params = frictionless();
  const ElongationTrajectory crosshead = smooth_stretch();
  const std::vector<double> pressure(crosshead.time().size(), 200e3);
  const Measurement plain = simulate_supplied_measurement(params, 0.167, crosshead, pressure, {});
  // The transducer reads 3 kPa high: the model is driven by 197 kPa, the channel still reads 200.
  const Measurement offset =
      simulate_supplied_measurement(params, 0.167, crosshead, pressure, {effect("sensor_offset:offset_Pa=3e3")});
  const std::vector<double> lower(pressure.size(), 197e3);
  const Measurement truth = simulate_supplied_measurement(params, 0.167, crosshead, lower, {});
  CHECK(identical(offset.force_N, truth.force_N));
  CHECK_FALSE(identical(offset.force_N, plain.force_N));
  CHECK(offset.gauge_pressure_Pa.front() == 200e3);
  CHECK_THROWS_WITH(simulate_supplied_measurement(params, 0.167, crosshead, pressure, {effect("leak")}),
                    Catch::Matchers::Contains("supplied test"));
}

TEST_CASE("supplied: a length outside the braid's range names the sample and the likely culprit",
          "[effects][supplied][validation]") {
  const ElongationTrajectory crosshead({0.0, 1.0, 2.0}, {0.0, 0.0, 0.2});
  const std::vector<double> pressure{100e3, 100e3, 100e3};
  CHECK_THROWS_WITH(simulate_supplied_measurement(MuscleParams(), 0.167, crosshead, pressure, {}),
                    Catch::Matchers::Contains("sample 3") && Catch::Matchers::Contains("initial_length_m"));
  CHECK_THROWS_WITH(simulate_supplied_measurement(MuscleParams(), 0.167, crosshead, {100e3}, {}),
                    Catch::Matchers::Contains("1 pressures for 3 samples"));
}
