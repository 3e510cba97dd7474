// RealtimeMuscle (muscle/realtime.hpp): the force a controller calls in its loop is the library's
// two-call force, bit for bit, inside the braid's range; outside it a status, no exception; and
// no heap allocation in any call. This executable replaces the global operator new to count
// allocations (bench/allocation_counter.hpp, which the benchmark of the same call counts with),
// so it is its own ctest area (label "realtime").

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <vector>

#include <catch2/catch.hpp>

#include "allocation_counter.hpp"
#include "pamkit/muscle/realtime.hpp"

namespace {

using allocation_counter::allocations;

using namespace pamkit;

/// The force as a controller computes it today: the throwing shape, then muscle_forces, then
/// the braid's slack (braid_tension is the identity when slack_band_N is 0).
double two_call_force(const MuscleParams& p, const BraidGeometry& geometry, double length_m, double gauge_Pa,
                      double velocity_m_per_s) {
  const double atmosphere = p.gas.atmospheric_pressure_Pa;
  const MuscleForces f = muscle_forces(geometry, geometry.shape(length_m), p.bladder, p.friction, atmosphere + gauge_Pa,
                                       atmosphere, velocity_m_per_s);
  return braid_tension(f.total, p.extensions.slack_band_N);
}

/// `count` lengths spread over the open range (min, max), ends excluded by half a step.
std::vector<double> lengths_inside(const RealtimeMuscle& m, int count) {
  std::vector<double> lengths;
  for (int i = 0; i < count; ++i) {
    lengths.push_back(m.min_length_m() + (m.max_length_m() - m.min_length_m()) * (i + 0.5) / count);
  }
  return lengths;
}

const std::vector<double> kGaugePressures_Pa = {-20e3, 0.0, 35e3, 207e3, 600e3};
const std::vector<double> kVelocities_m_per_s = {-0.05, -1e-3, 0.0, 2.5e-3, 0.05};

}  // namespace

TEST_CASE("Inside the braid's range the real-time force is the two-call force, bit for bit", "[realtime]") {
  // Exact equality, not a tolerance: both paths run the same functions (shape_unchecked is what
  // shape returns after its check; supplied_force at branch 0 is braid_tension of muscle_forces'
  // total), so any difference is a second implementation that has crept in.
  MuscleParams thesis;  // PAM 2, the thesis's bladder, Kf = 1 s/m, the braid pushes
  MuscleParams flat_ends;
  flat_ends.build.cone_generator_m = 0.0;
  MuscleParams neo_hookean_slack;  // a moulded membrane, sharp friction, a braid that goes slack
  neo_hookean_slack.bladder = BladderLaw::neo_hookean(1.5e6);
  neo_hookean_slack.friction.sharpness_s_per_m = 200.0;
  neo_hookean_slack.extensions.slack_band_N = 5.0;
  neo_hookean_slack.gas.atmospheric_pressure_Pa = 95e3;

  for (const MuscleParams& params : {thesis, flat_ends, neo_hookean_slack}) {
    const RealtimeMuscle muscle(params);
    const BraidGeometry geometry(params.build);
    long compared = 0;
    long in_slack_band = 0;
    for (double L : lengths_inside(muscle, 41)) {
      for (double p : kGaugePressures_Pa) {
        for (double v : kVelocities_m_per_s) {
          const RealtimeForce f = muscle.force(L, p, v);
          const double expected = two_call_force(params, geometry, L, p, v);
          INFO("L = " << L << " m, p = " << p << " Pa, v = " << v << " m/s");
          REQUIRE(f.status == ForceStatus::ok);
          CHECK(f.force_N == expected);
          ++compared;
          const double atmosphere = params.gas.atmospheric_pressure_Pa;
          const double unslacked =
              muscle_forces(geometry, geometry.shape(L), params.bladder, params.friction, atmosphere + p, atmosphere, v)
                  .total;
          if (std::abs(unslacked) < params.extensions.slack_band_N) ++in_slack_band;
        }
      }
    }
    CHECK(compared == 41 * 5 * 5);
    // The slack case must reach the blend of braid_tension, or it would test nothing of it.
    if (params.extensions.slack_band_N > 0.0) CHECK(in_slack_band > 0);
  }
}

TEST_CASE("The lengths next to the ends of the range still give the two-call force", "[realtime]") {
  const MuscleParams params;
  const RealtimeMuscle muscle(params);
  const BraidGeometry geometry(params.build);
  const double inf = std::numeric_limits<double>::infinity();
  for (double L : {std::nextafter(muscle.min_length_m(), inf), std::nextafter(muscle.max_length_m(), -inf)}) {
    const RealtimeForce f = muscle.force(L, 207e3, 0.0);
    INFO("L = " << L << " m");
    CHECK(f.status == ForceStatus::ok);
    CHECK(f.force_N == two_call_force(params, geometry, L, 207e3, 0.0));
  }
}

TEST_CASE("Outside the range, or for input that is not finite, a status and 0 N instead of an exception",
          "[realtime]") {
  const RealtimeMuscle muscle{MuscleParams{}};
  STATIC_REQUIRE(noexcept(muscle.force(0.0, 0.0, 0.0)));
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double lo = muscle.min_length_m();
  const double hi = muscle.max_length_m();
  struct Case {
    double length_m, gauge_Pa, velocity_m_per_s;
    ForceStatus status;
  };
  const std::vector<Case> cases = {
      {lo, 207e3, 0.0, ForceStatus::too_short},
      {std::nextafter(lo, 0.0), 207e3, 0.0, ForceStatus::too_short},
      {0.0, 207e3, 0.0, ForceStatus::too_short},
      {-1.0, 207e3, 0.0, ForceStatus::too_short},
      {-inf, 207e3, 0.0, ForceStatus::too_short},
      {hi, 207e3, 0.0, ForceStatus::too_long},
      {std::nextafter(hi, inf), 0.0, 0.0, ForceStatus::too_long},
      {10.0, 207e3, 0.1, ForceStatus::too_long},
      {inf, 207e3, 0.0, ForceStatus::too_long},
      {nan, 207e3, 0.0, ForceStatus::not_finite},
      {0.19, nan, 0.0, ForceStatus::not_finite},
      {0.19, inf, 0.0, ForceStatus::not_finite},
      {0.19, 207e3, nan, ForceStatus::not_finite},
      {0.19, 207e3, -inf, ForceStatus::not_finite},
  };
  for (const Case& c : cases) {
    INFO("L = " << c.length_m << " m, p = " << c.gauge_Pa << " Pa, v = " << c.velocity_m_per_s << " m/s");
    const RealtimeForce f = muscle.force(c.length_m, c.gauge_Pa, c.velocity_m_per_s);
    CHECK(f.status == c.status);
    CHECK(f.force_N == 0.0);
  }
  // The two-call path throws for the same lengths: what the status replaces.
  CHECK_THROWS_AS(muscle.geometry().shape(hi), InvalidInput);
  CHECK_THROWS_AS(muscle.geometry().shape(lo), InvalidInput);
}

TEST_CASE("The real-time force allocates nothing, in range or out of it", "[realtime]") {
  MuscleParams params;
  params.extensions.slack_band_N = 5.0;
  const RealtimeMuscle muscle(params);
  std::vector<double> lengths = lengths_inside(muscle, 101);
  lengths.push_back(muscle.min_length_m() * 0.5);
  lengths.push_back(muscle.max_length_m() * 1.5);
  lengths.push_back(std::numeric_limits<double>::quiet_NaN());

  // The counter sees an allocation, and the library's throwing path makes some.
  long before = allocations.load();
  std::vector<double>* probe = new std::vector<double>(3);
  delete probe;
  REQUIRE(allocations.load() > before);
  before = allocations.load();
  try {
    (void)muscle.geometry().shape(muscle.max_length_m() * 1.5);
  } catch (const InvalidInput&) {
  }
  CHECK(allocations.load() > before);

  before = allocations.load();
  double sum = 0.0;
  long calls = 0;
  for (int round = 0; round < 20; ++round) {
    for (double L : lengths) {
      for (double p : kGaugePressures_Pa) {
        for (double v : kVelocities_m_per_s) {
          sum += muscle.force(L, p, v).force_N;
          ++calls;
        }
      }
    }
  }
  const long counted = allocations.load() - before;
  CHECK(counted == 0);
  CHECK(calls == 20 * 104 * 5 * 5);
  CHECK(std::isfinite(sum));
}

TEST_CASE("The pressurise/vent hysteresis is left out: the force lies between its two branches", "[realtime]") {
  MuscleParams params;
  params.extensions.pressure_hysteresis = 0.05;
  const RealtimeMuscle muscle(params);
  const BraidGeometry geometry(params.build);
  for (double L : lengths_inside(muscle, 11)) {
    const MuscleShape shape = geometry.shape(L);
    const double pressurising = detail::supplied_force(geometry, params, shape, 207e3, 0.0, +1.0);
    const double venting = detail::supplied_force(geometry, params, shape, 207e3, 0.0, -1.0);
    const double f = muscle.force(L, 207e3, 0.0).force_N;
    INFO("L = " << L << " m");
    CHECK(pressurising < f);
    CHECK(f < venting);
  }
}

TEST_CASE("Construction validates the parameters", "[realtime]") {
  MuscleParams params;
  params.build.fiber_count = -3;
  CHECK_THROWS_AS(RealtimeMuscle(params), InvalidParameter);
  params = MuscleParams{};
  params.friction.sharpness_s_per_m = -1.0;
  CHECK_THROWS_AS(RealtimeMuscle(params), InvalidParameter);
}

namespace {

/// An embedded DMSP-10-like muscle with Maxwell-slip friction and no membrane.
MuscleParams slipping_dmsp() {
  MuscleParams params;
  params.build.length_m = 0.25;
  params.build.diameter_m = 0.01;
  params.build.bladder_diameter_m = 0.01;
  params.build.bladder_thickness_m = 0.5e-3;
  params.build.fiber_thickness_m = 0.0;
  params.build.end_diameter_m = 0.005;
  params.build.cone_generator_m = 0.0;
  params.build.end_zone_m = 0.008;
  params.build.construction = Construction::embedded;
  params.build.fiber_revolutions = fiber_revolutions_for_braid_angle(params.build, 22.0);
  params.bladder = BladderLaw::none();
  params.extensions.slip_force_N = 180.0;
  params.extensions.slip_distance_m = 0.02;
  return params;
}

}  // namespace

TEST_CASE("With friction that remembers, the workspace's force allocates nothing and throws nothing",
          "[realtime][slip]") {
  // Lengths and pressures that take the muscle slack and taut: the slack braid's search runs too.
  // (That this force is static_forces' row by row is tests/cpp/embedded.test.cpp's.)
  const MuscleParams params = slipping_dmsp();
  const RealtimeMuscle muscle(params);
  RealtimeWorkspace workspace = muscle.rest();
  STATIC_REQUIRE(noexcept(muscle.force(workspace, 0.2, 0.0, 0.0)));
  const long before = allocations.load();
  long slack = 0;
  long taut = 0;
  for (int k = 0; k < 600; ++k) {
    const RealtimeForce f =
        muscle.force(workspace, 0.24 - 0.02 * std::sin(0.011 * k), 300e3 + 280e3 * std::sin(0.023 * k), 0.0);
    REQUIRE(f.status == ForceStatus::ok);
    (f.force_N < 0.5 ? slack : taut) += 1;
  }
  CHECK(allocations.load() == before);
  CHECK(slack > 0);
  CHECK(taut > 0);
  // Out of range: a status, and the workspace as it was.
  const HeldBraidState kept = workspace.braid;
  CHECK(muscle.force(workspace, muscle.max_length_m() * 1.5, 300e3, 0.0).status == ForceStatus::too_long);
  CHECK(workspace.braid.braid_length_m == kept.braid_length_m);
  // Without slip elements the workspace changes nothing: the memoryless force.
  MuscleParams memoryless = params;
  memoryless.extensions.slip_force_N = 0.0;
  const RealtimeMuscle plain(memoryless);
  RealtimeWorkspace unused = plain.rest();
  for (double L : {0.2, 0.23, 0.245})
    CHECK(plain.force(unused, L, 300e3, 0.01).force_N == plain.force(L, 300e3, 0.01).force_N);
}

TEST_CASE("A series compliance: the one call and the workspace agree bit for bit and allocate nothing",
          "[realtime][series]") {
  // Without slip elements the braid's place has no memory: the one call solves it afresh and the
  // workspace carries it, the same number; with them, the workspace's force allocates nothing.
  MuscleParams params = slipping_dmsp();
  params.build.series_compliance_m_per_N = 4e-6;
  params.extensions.slip_force_N = 0.0;
  const RealtimeMuscle plain(params);
  RealtimeWorkspace unused = plain.rest();
  const long before = allocations.load();
  int pulling = 0;
  for (int k = 0; k < 200; ++k) {
    const double L = 0.24 - 0.02 * std::sin(0.031 * k);
    const double p = 300e3 + 280e3 * std::sin(0.047 * k);
    const RealtimeForce f = plain.force(L, p, 0.0);
    REQUIRE(f.status == ForceStatus::ok);
    CHECK(plain.force(unused, L, p, 0.0).force_N == f.force_N);
    pulling += f.force_N > 1.0;
  }
  CHECK(pulling > 20);
  params.extensions.slip_force_N = 180.0;
  const RealtimeMuscle slipping(params);
  RealtimeWorkspace workspace = slipping.rest();
  for (int k = 0; k < 200; ++k) {
    REQUIRE(
        slipping.force(workspace, 0.24 - 0.02 * std::sin(0.031 * k), 300e3 + 280e3 * std::sin(0.047 * k), 0.0).status ==
        ForceStatus::ok);
  }
  CHECK(allocations.load() == before);
}
