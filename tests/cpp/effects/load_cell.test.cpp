// load_cell: the force reads offset + F (1 + c F) exactly, and nothing else changes.

#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

using namespace pamkit_test;

TEST_CASE("load_cell: the force reads offset + F (1 + c F) exactly", "[effects][load_cell]") {
  const ElongationTrajectory crosshead = thesis_protocol(0.05, 2.5e-3, 1, 0.1);
  const Measurement truth = measure(MuscleParams(), table_c2_90(), crosshead, {});
  const Measurement m =
      measure(MuscleParams(), table_c2_90(), crosshead, {"load_cell:offset_N=-4.5,nonlinearity_per_kN=0.12"});
  for (std::size_t k = 0; k < truth.time_s.size(); ++k) {
    INFO("sample " << k);
    const double f = truth.force_N[k];
    CHECK(m.force_N[k] == -4.5 + f * (1.0 + 0.12e-3 * f));
  }
  CHECK(identical(m.gauge_pressure_Pa, truth.gauge_pressure_Pa));
  CHECK(identical(m.temperature_K, truth.temperature_K));
}

TEST_CASE("load_cell: the nonlinearity is the relative error per kN", "[effects][load_cell]") {
  // A 300 N force read with 0.1/kN reads 3 % high: the unit the plausible range is stated in.
  Measurement m;
  m.force_N = {0.0, 300.0};
  EffectCatalog::builtin().parse("load_cell:offset_N=0,nonlinearity_per_kN=0.1")->apply_to_measurement(m);
  CHECK(m.force_N[0] == 0.0);
  CHECK(m.force_N[1] == Approx(309.0).epsilon(1e-15));
}
