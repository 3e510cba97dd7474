// thermometer: the temperature reads the gas's plus a constant, and nothing else changes.

#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

using namespace pamkit_test;

TEST_CASE("thermometer: the temperature reads the gas's plus the offset", "[effects][thermometer]") {
  const ElongationTrajectory crosshead = thesis_protocol(0.05, 2.5e-3, 1, 0.1);
  const Measurement truth = measure(MuscleParams(), table_c2_90(), crosshead, {});
  const Measurement m = measure(MuscleParams(), table_c2_90(), crosshead, {"thermometer:offset_K=-1.25"});
  for (std::size_t k = 0; k < truth.time_s.size(); ++k) {
    INFO("sample " << k);
    CHECK(m.temperature_K[k] == truth.temperature_K[k] + -1.25);
  }
  CHECK(identical(m.force_N, truth.force_N));
  CHECK(identical(m.gauge_pressure_Pa, truth.gauge_pressure_Pa));
}
