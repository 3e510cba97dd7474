// braid_slack in a supplied test: a braid that cannot push leaves the thesis's force alone where
// the braid is taut, carries nothing where the thesis's braid would push, and joins the two
// within a quarter of its band.

#include <algorithm>
#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include "effect_test_support.hpp"
#include "pamkit/muscle/free_inflation.hpp"

using namespace pamkit_test;

TEST_CASE(
    "braid_slack: in a supplied sweep the force is the thesis's where the braid is taut and zero where it "
    "would push",
    "[effects][braid_slack]") {
  // PAM 2 held at its free length at 150 kPa while the supplied pressure rises from 20 to 300 kPa:
  // below 150 kPa the muscle is held shorter than its free length, and the thesis's braid pushes.
  const MuscleParams params;
  const double length =
      free_inflation(BraidGeometry(params.build), params.bladder, params.gas.atmospheric_pressure_Pa, 150e3).length_m;
  std::vector<double> time, pressure;
  for (int k = 0; k <= 28; ++k) {
    time.push_back(0.5 * k);
    pressure.push_back(20e3 + 10e3 * k);
  }
  const ElongationTrajectory held(time, std::vector<double>(time.size(), 0.0));
  const double band = 2.0;
  const Measurement thesis = simulate_supplied_measurement(params, length, held, pressure, {});
  const Measurement slack =
      simulate_supplied_measurement(params, length, held, pressure, {effect("braid_slack:band_N=2")});
  REQUIRE(*std::min_element(thesis.force_N.begin(), thesis.force_N.end()) < -band);  // the sweep spans both
  REQUIRE(max_of(thesis.force_N) > band);
  for (std::size_t k = 0; k < time.size(); ++k) {
    const double pushing = thesis.force_N[k];
    INFO(pressure[k] << " Pa: thesis " << pushing << " N, slack braid " << slack.force_N[k] << " N");
    if (pushing >= band) {
      CHECK(slack.force_N[k] == pushing);  // taut: untouched
    } else if (pushing <= -band) {
      CHECK(slack.force_N[k] == 0.0);  // slack: nothing
    } else {
      // The smooth join lies above the slack braid's max(F, 0), by at most band / 4 (at F = 0).
      CHECK(slack.force_N[k] >= std::max(pushing, 0.0));
      CHECK(slack.force_N[k] <= std::max(pushing, 0.0) + 0.25 * band);
    }
  }
}
