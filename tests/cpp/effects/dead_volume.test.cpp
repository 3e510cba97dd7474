// dead_volume against the isothermal closed form p0 (V0 + Vd) / (V + Vd): the pressure swing is
// scaled down evenly, at every rate.

#include <algorithm>
#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

using namespace pamkit_test;

TEST_CASE("dead_volume: the isothermal pressure is p0 (V0 + Vd) / (V + Vd); the swing is scaled down evenly",
          "[effects][dead_volume]") {
  const double fraction = 0.2;
  const MuscleParams params;
  const InitialState initial = table_c2_90();
  const BraidGeometry geometry(params.build);
  const double v0 = geometry.shape(initial.length_m).gas_volume;
  const double vd = fraction * v0;
  const double p0 = 236.63e3 + kAtmosphere_Pa;

  for (const double speed : {2.5e-3, 25e-3}) {
    const ElongationTrajectory crosshead = thesis_protocol(0.05, speed, 2, 0.05 / speed / 200.0);
    const Measurement with = measure(params, initial, crosshead, {"dead_volume:volume_fraction=0.2"});
    const Measurement without = measure(params, initial, crosshead, {});
    double v_min = v0;
    for (std::size_t k = 0; k < with.time_s.size(); ++k) {
      const double v = geometry.shape(initial.length_m + with.elongation_m[k]).gas_volume;
      v_min = std::min(v_min, v);
      INFO("speed " << speed << " m/s, sample " << k);
      // An isothermal closed mass has no memory: the closed form holds to rounding.
      CHECK_REL(with.gauge_pressure_Pa[k] + kAtmosphere_Pa, p0 * (v0 + vd) / (v + vd), 1e-12);
    }
    auto swing = [](const std::vector<double>& p) {
      return *std::max_element(p.begin(), p.end()) - *std::min_element(p.begin(), p.end());
    };
    const double ratio = swing(with.gauge_pressure_Pa) / swing(without.gauge_pressure_Pa);
    // p_top - p_0 = p0 (V0 + Vd) (1/(Vmin + Vd) - 1/(V0 + Vd)) against p0 V0 (1/Vmin - 1/V0):
    // the ratio is Vmin / (Vmin + Vd) = 1 / (1 + f V0 / Vmin), below 1 / (1 + f) since Vmin < V0.
    const double closed_form = v_min / (v_min + vd);
    INFO("swing ratio " << ratio << ", closed form " << closed_form);
    CHECK_REL(ratio, closed_form, 1e-10);
    CHECK(ratio < 1.0 / (1.0 + fraction));
  }
}
