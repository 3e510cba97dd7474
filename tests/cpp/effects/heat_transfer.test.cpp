// heat_transfer shows its signature in simulated bench tests: a pressure loop that grows with
// rate while the cycle is slow against tau, and relaxation to the isothermal pressure in holds.

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

namespace {

using namespace pamkit_test;

// Area of the pressure-elongation loop [Pa m] over the last of three cycles to 5 cm at `speed`,
// 200 samples per stroke.
double pressure_loop_area(const std::vector<std::string>& specs, double speed_m_per_s) {
  const double stroke = 0.05;
  const ElongationTrajectory crosshead = thesis_protocol(stroke, speed_m_per_s, 3, stroke / speed_m_per_s / 200.0);
  const Measurement m = measure(MuscleParams(), table_c2_90(), crosshead, specs);
  const std::size_t last = m.time_s.size() - 1;
  return loop_area(m.elongation_m, m.gauge_pressure_Pa, last - 400, last);
}

}  // namespace

TEST_CASE(
    "heat_transfer: the pressure-elongation loop opens, grows with rate while the cycle is slow against tau, and "
    "closes again when it is fast",
    "[effects][heat_transfer]") {
  const std::vector<std::string> heat{"heat_transfer:time_constant_s=2"};
  // Isothermal baseline: the pressure is a function of the volume alone, so the loop has no area
  // beyond rounding (compared with the loop's bounding box, ~200 kPa x 0.05 m).
  CHECK(std::abs(pressure_loop_area({}, 2.5e-3)) < 1e-12 * 200e3 * 0.05);

  // The heat the gas loses per cycle is the loop's area (times dV/dL). For a first-order exchange
  // it is proportional to w tau / (1 + (w tau)^2): it grows with rate while w tau < 1 and falls
  // beyond, where the gas has no time to exchange and the loop closes on the adiabat.
  // Strokes of 5 cm: 2.5 mm/s is a 40 s cycle (w tau = 0.31), 5 mm/s 20 s (0.63), 100 mm/s 1 s (12.6).
  const double slow = pressure_loop_area(heat, 2.5e-3);
  const double faster = pressure_loop_area(heat, 5e-3);
  const double near_peak = pressure_loop_area(heat, 10e-3);
  const double fast = pressure_loop_area(heat, 100e-3);
  INFO("loop areas [Pa m]: 2.5 mm/s " << slow << ", 5 mm/s " << faster << ", 10 mm/s " << near_peak << ", 100 mm/s "
                                      << fast);
  CHECK(slow > 0.0);  // pressure higher while stretching (compressing) than while returning
  CHECK(faster > slow);
  CHECK(near_peak > faster);
  CHECK(fast < near_peak);
}

TEST_CASE("heat_transfer: during a hold the pressure relaxes to the isothermal value as exp(-t/tau)",
          "[effects][heat_transfer]") {
  // At a fixed length the volume is fixed, so m cv dT/dt = -m cv (T - T_ambient) / tau: T - T_ambient
  // decays as exp(-t/tau) and so does p - p_isothermal = m R (T - T_ambient) / V, exactly.
  const double tau = 2.0;
  const double hold = 3.0 * tau;
  const double stroke = 0.05;
  const double speed = 2.5e-3;
  const ElongationTrajectory crosshead = thesis_protocol(stroke, speed, 1, 0.1, hold);
  const Measurement m = measure(MuscleParams(), table_c2_90(), crosshead, {"heat_transfer:time_constant_s=2"});
  const Measurement isothermal = measure(MuscleParams(), table_c2_90(), crosshead, {});

  // The holds start at the top (t = 20 s) and at the bottom (t = 20 + 6 + 20 s) of the cycle.
  for (const double start : {stroke / speed, 2.0 * stroke / speed + hold}) {
    const std::size_t k0 = sample_at(m.time_s, start);
    const std::size_t k1 = sample_at(m.time_s, start + hold);
    REQUIRE(m.elongation_m[k0] == m.elongation_m[k1]);
    const double excess0 = m.gauge_pressure_Pa[k0] - isothermal.gauge_pressure_Pa[k0];
    INFO("hold from t = " << m.time_s[k0] << " s: excess over isothermal " << excess0 << " Pa");
    CHECK(std::abs(excess0) > 1e3);  // the ramp left the gas far from isothermal
    for (std::size_t k = k0; k <= k1; ++k) {
      const double expected = excess0 * std::exp(-(m.time_s[k] - m.time_s[k0]) / tau);
      const double excess = m.gauge_pressure_Pa[k] - isothermal.gauge_pressure_Pa[k];
      INFO("t = " << m.time_s[k] << " s: excess " << excess << " Pa, expected " << expected);
      // CVODES at rtol 1e-10 holds T to ~1e-9 relative; on ~400 kPa absolute that is ~1e-2 Pa.
      CHECK(std::abs(excess - expected) < 1e-7 * (m.gauge_pressure_Pa[k] + kAtmosphere_Pa));
    }
  }
}
