// slip_hysteresis in a supplied test: a muscle stretched and returned at a fixed supplied pressure
// by a crosshead traces the Maxwell-slip loop of its elements over its elastic force, whatever the
// rate, and keeps what they hold when the crosshead stops.

#include <cmath>
#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

using namespace pamkit_test;

TEST_CASE("slip_hysteresis: a stretch and return at fixed pressure is the elastic force plus the elements' loop",
          "[effects][slip_hysteresis]") {
  // PAM 2 at 200 kPa, stretched 10 mm from its free length and returned, in 0.5 mm steps. The muscle
  // was mounted at rest (its deflated length) and contracted to the free length: the elements
  // start there holding -f. Going out they spring back over 2 delta to +f, coming back to -f
  // (Masing); the force is the elastic one plus what they hold, settled or not (a tenfold slower
  // crosshead), and the crosshead held still at the end keeps it.
  MuscleParams params;  // PAM 2, a sleeve: its braid pushes, so no slack hides the loop
  params.friction = FrictionParams{0.0, 0.0, 0.0, 0.0, 0.0};
  const double f = 30.0;
  const double delta = 0.004;
  const EffectPtr slip = effect("slip_hysteresis:slip_force_N=30,slip_distance_m=0.004");
  const double start =
      free_inflation(BraidGeometry(params.build), params.bladder, params.gas.atmospheric_pressure_Pa, 200e3).length_m;
  std::vector<double> stretch;
  for (int k = 0; k <= 20; ++k) stretch.push_back(0.0005 * k);
  for (int k = 19; k >= 0; --k) stretch.push_back(0.0005 * k);
  stretch.push_back(0.0);                                     // held still
  const std::vector<double> pressure(stretch.size(), 200e3);  // [Pa]
  for (const double step_s : {0.5, 5.0}) {
    std::vector<double> time;
    for (std::size_t k = 0; k < stretch.size(); ++k) time.push_back(step_s * static_cast<double>(k));
    const ElongationTrajectory crosshead(time, stretch);
    const Measurement with = simulate_supplied_measurement(params, start, crosshead, pressure, {slip});
    const Measurement without = simulate_supplied_measurement(params, start, crosshead, pressure, {});
    SlipState elements;
    slip_move(elements, f, delta, start - params.build.length_m);
    for (std::size_t k = 0; k < stretch.size(); ++k) {
      if (k > 0) slip_move(elements, f, delta, stretch[k] - stretch[k - 1]);
      INFO(step_s << " s per step, sample " << k);
      CHECK(with.force_N[k] - without.force_N[k] == Approx(elements.total_N()).margin(1e-9));
    }
    // Out 10 mm (past 2 delta from -f): the elements hold f; back to the start, -f again.
    CHECK_REL(with.force_N[0] - without.force_N[0], -f, 1e-12);
    CHECK_REL(with.force_N[20] - without.force_N[20], f, 1e-12);
    CHECK_REL(with.force_N[40] - without.force_N[40], -f, 1e-12);
    CHECK(with.force_N.back() == with.force_N[40]);
  }
}
