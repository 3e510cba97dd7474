// sensor_offset: the pressure reads gain x p + offset exactly, and nothing else changes.

#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

using namespace pamkit_test;

TEST_CASE("sensor_offset: the pressure reads gain x p + offset exactly", "[effects][sensor_offset]") {
  const ElongationTrajectory crosshead = thesis_protocol(0.05, 2.5e-3, 1, 0.1);
  const Measurement truth = measure(MuscleParams(), table_c2_90(), crosshead, {});
  const Measurement m = measure(MuscleParams(), table_c2_90(), crosshead, {"sensor_offset:offset_Pa=-7.5e3,gain=1.04"});
  for (std::size_t k = 0; k < truth.time_s.size(); ++k) {
    INFO("sample " << k);
    CHECK(m.gauge_pressure_Pa[k] == 1.04 * truth.gauge_pressure_Pa[k] + -7.5e3);
  }
  CHECK(identical(m.force_N, truth.force_N));
  CHECK(identical(m.temperature_K, truth.temperature_K));
}
