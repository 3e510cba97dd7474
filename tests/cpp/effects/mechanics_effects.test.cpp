// The effects on the muscle's mechanics show their signatures: fixture_slack (force flat for the
// slack's travel after each reversal, the loop shifted), bladder_viscoelasticity (force
// hysteresis that grows with rate, strongest at low pressure, with no pressure hysteresis),
// fiber_compliance (softer at high force; the braid shorter by F Lym / (N EA)).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

namespace {

using namespace pamkit_test;

double max_of(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

}  // namespace

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
    // state does not change and its friction is zero, so the force is the same to the bit.
    // (At a turning point itself the force still carries the friction of the segment before it.)
    const std::size_t first = (r == 0) ? 0 : r + 1;
    std::size_t last = first;
    while (last + 1 < c.size() && std::abs(c[last + 1] - c[r]) <= slack * (1.0 + 1e-9)) ++last;
    INFO("reversal at t = " << m.time_s[r] << " s: flat from sample " << first << " to " << last);
    CHECK(last - r == 8);
    for (std::size_t k = first; k <= last; ++k) CHECK(m.force_N[k] == m.force_N[first]);
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

namespace {

// Force hysteresis added by the bladder's Maxwell branch [N m]: the force-elongation loop's area
// over the second of two cycles, less the baseline's (whose friction makes a loop too).
struct Hysteresis {
  double viscous_area;   ///< [N m]
  double work_scale;     ///< peak force x stroke [N m]
  double pressure_diff;  ///< largest |p - p_baseline| [kPa]
};

Hysteresis viscoelastic_hysteresis(const MuscleParams& params, const InitialState& initial, double stroke,
                                   double speed) {
  const ElongationTrajectory crosshead = thesis_protocol(stroke, speed, 2, stroke / speed / 200.0);
  const Measurement m = measure(params, initial, crosshead, {"bladder_viscoelasticity:time_constant_s=2,strength=1"});
  const Measurement baseline = measure(params, initial, crosshead, {});
  const std::size_t last = m.time_s.size() - 1;
  Hysteresis h{};
  h.viscous_area = loop_area(m.elongation_m, m.force_N, last - 400, last) -
                   loop_area(baseline.elongation_m, baseline.force_N, last - 400, last);
  h.work_scale = max_of(baseline.force_N) * stroke;
  for (std::size_t k = 0; k <= last; ++k)
    h.pressure_diff = std::max(h.pressure_diff, std::abs(m.pressure_kPa[k] - baseline.pressure_kPa[k]));
  return h;
}

}  // namespace

TEST_CASE(
    "bladder_viscoelasticity: force hysteresis grows with rate, is larger relative to force at low pressure, and "
    "leaves the pressure alone",
    "[effects][bladder_viscoelasticity]") {
  // High pressure: PAM 2, table C.3's 95 % test (0.165 m, 298.40 kPa, 57.3 mm).
  // Low pressure: PAM 1 (deflated 0.223 m, table 3.4) at 35 kPa, 0.185 m, 36.1 mm (tables 3.4-3.5).
  MuscleParams pam1;
  pam1.build.length_m = 0.223;
  struct Case {
    const char* name;
    MuscleParams params;
    InitialState initial;
    double stroke;
  };
  const Case high{"276 kPa (PAM 2)", MuscleParams(), {0.165, 298.40e3}, 0.0573};
  const Case low{"35 kPa (PAM 1)", pam1, {0.185, 35e3}, 0.0361};

  double relative_at_2_5[2] = {0.0, 0.0};
  int i = 0;
  for (const Case& c : {high, low}) {
    // tau = 2 s against cycles of 46 s and 23 s (high) or 29 s and 14 s (low): w tau < 1, where a
    // Maxwell branch dissipates more per cycle the faster it is driven.
    const Hysteresis slow = viscoelastic_hysteresis(c.params, c.initial, c.stroke, 2.5e-3);
    const Hysteresis fast = viscoelastic_hysteresis(c.params, c.initial, c.stroke, 5e-3);
    INFO(c.name << ": viscous loop area " << slow.viscous_area << " N m at 2.5 mm/s, " << fast.viscous_area
                << " N m at 5 mm/s; peak force x stroke " << slow.work_scale << " N m");
    CHECK(slow.viscous_area > 0.0);
    CHECK(fast.viscous_area > slow.viscous_area);
    // The branch acts on the force through the bladder's strains; the isothermal gas's pressure
    // depends on the volume alone, which the branch does not change. The runs' integrator steps
    // differ (the branch's states join the error test), so the two agree to rounding: 1e-9 kPa
    // is ~1e-11 of these pressures.
    CHECK(slow.pressure_diff <= 1e-9);
    CHECK(fast.pressure_diff <= 1e-9);
    relative_at_2_5[i++] = slow.viscous_area / slow.work_scale;
  }
  INFO("viscous hysteresis / (peak force x stroke): high pressure " << relative_at_2_5[0] << ", low pressure "
                                                                    << relative_at_2_5[1]);
  CHECK(relative_at_2_5[1] > relative_at_2_5[0]);
}

TEST_CASE("fiber_compliance: the braid is shorter by F Lym / (N EA), and the muscle is softer at high force",
          "[effects][fiber_compliance]") {
  const double ea = 300.0;
  MuscleParams compliant;
  compliant.extensions.fiber_compliance_per_N = 1.0 / ea;
  const MuscleParams rigid;
  const InitialState initial = table_c2_90();
  const MuscleModel model(compliant, initial);
  const MuscleModel rigid_model(rigid, initial);
  const double lym = model.geometry().fiber_length();
  const double fibers = compliant.build.fiber_count;

  SECTION("the series spring, at rest") {
    for (const double length : {0.17, 0.19, 0.2165}) {
      const MuscleOutputs out = model.evaluate(length, 0.0, model.initial());
      INFO("length " << length << " m: force " << out.forces.total << " N, braid " << out.braid_length_m << " m");
      REQUIRE(out.forces.friction == 0.0);
      // The fibers' tensions sum to the force; each stretches by T Lym / EA.
      CHECK_REL(length - out.braid_length_m, out.forces.total * lym / (fibers * ea), 1e-9);
      // The same force is what the rigid muscle makes at the braid's length.
      CHECK_REL(out.forces.total, rigid_model.evaluate(out.braid_length_m, 0.0, rigid_model.initial()).forces.total,
                1e-12);
    }
  }

  SECTION("the same crosshead travel gives less force, the more so the higher the force") {
    const ElongationTrajectory crosshead = thesis_protocol(0.05, 2.5e-3, 1, 0.1);
    const Measurement m = measure(rigid, initial, crosshead, {"fiber_compliance:stiffness_N=300"});
    const Measurement baseline = measure(rigid, initial, crosshead, {});
    const std::size_t top = tops(m.elongation_m).front();
    const std::size_t quarter = top / 4;
    const double drop_top = 1.0 - m.force_N[top] / baseline.force_N[top];
    const double drop_quarter = 1.0 - m.force_N[quarter] / baseline.force_N[quarter];
    INFO("force at the top " << m.force_N[top] << " N vs " << baseline.force_N[top] << " N (" << drop_top
                             << " lower); at a quarter stroke " << drop_quarter << " lower");
    CHECK(drop_quarter > 0.0);
    CHECK(drop_top > drop_quarter);
    // The braid travels less than the crosshead, so the gas is compressed less.
    CHECK(m.pressure_kPa[top] < baseline.pressure_kPa[top]);
  }
}
