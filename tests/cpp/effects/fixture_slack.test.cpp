// fixture_slack: the force stays flat for the slack's travel after each reversal, and the loop is
// shifted by the slack.

#include <cmath>
#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

using namespace pamkit_test;

TEST_CASE("fixture_slack: the force stays flat for the slack's travel after each reversal; the loop is shifted",
          "[effects][fixture_slack]") {
  const double slack = 2e-3;
  const double stroke = 0.05;
  // 2.5 mm/s sampled at 10 Hz: 0.25 mm per sample, so the slack is 8 samples of travel.
  const ElongationTrajectory crosshead = thesis_protocol(stroke, 2.5e-3, 2, 0.1);
  const Measurement m = measure(MuscleParams(), table_c2_90(), crosshead, {"fixture_slack:slack_m=0.002"});
  const Measurement baseline = measure(MuscleParams(), table_c2_90(), crosshead, {});
  const std::vector<double>& c = m.elongation_m;  // the crosshead's, as the machine records it
  REQUIRE(identical(c, crosshead.elongation()));

  // Reversals: the start, and every sample where the crosshead turns.
  std::vector<std::size_t> reversals{0};
  for (std::size_t k = 1; k + 1 < c.size(); ++k) {
    if ((c[k] - c[k - 1]) * (c[k + 1] - c[k]) < 0.0) reversals.push_back(k);
  }
  REQUIRE(reversals.size() == 4);  // start, top, bottom, top
  for (const std::size_t r : reversals) {
    // While the crosshead takes up the play the muscle stands still: with the isothermal gas its
    // state does not change and its friction is zero, so the force is the same to the geometry's
    // precision: its Newton iteration, warm-started from the previous sample's shape, stops at
    // 47 bits (7e-15 relative), so the same length may differ in the last bits with the build.
    // (At a turning point itself the force still carries the friction of the segment before it.)
    const std::size_t first = (r == 0) ? 0 : r + 1;
    std::size_t last = first;
    while (last + 1 < c.size() && std::abs(c[last + 1] - c[r]) <= slack * (1.0 + 1e-9)) ++last;
    INFO("reversal at t = " << m.time_s[r] << " s: flat from sample " << first << " to " << last);
    CHECK(last - r == 8);
    for (std::size_t k = first; k <= last; ++k) {
      CHECK(std::abs(m.force_N[k] - m.force_N[first]) <= 1e-12 * std::abs(m.force_N[first]));
    }
    CHECK(std::abs(m.force_N[last + 1] - m.force_N[last]) > 0.1);  // then the muscle moves
  }

  // Shifted: stretching, the muscle is `slack` behind the crosshead; returning, it is at the
  // crosshead (it starts back only once the play is taken up). The isothermal muscle has no
  // memory, so its force is the baseline's at the same muscle elongation and speed.
  const std::size_t top = reversals[1];
  for (std::size_t k = 9; k <= top; ++k) {
    INFO("stretching, crosshead at " << c[k] << " m");
    CHECK_REL(m.force_N[k], baseline.force_N[k - 8], 1e-9);
  }
  for (std::size_t k = top + 9; k <= reversals[2]; ++k) {
    INFO("returning, crosshead at " << c[k] << " m");
    CHECK_REL(m.force_N[k], baseline.force_N[k], 1e-9);
  }
  // The peak force is the baseline's for a stroke shorter by the slack.
  const Measurement shorter =
      measure(MuscleParams(), table_c2_90(), thesis_protocol(stroke - slack, 2.5e-3, 2, 0.1), {});
  CHECK_REL(max_of(m.force_N), max_of(shorter.force_N), 1e-12);
}
