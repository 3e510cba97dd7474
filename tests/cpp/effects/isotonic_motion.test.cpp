// isotonic_motion, a mass on the muscle over time, against what it must reduce to: the
// quasi-static path of isotonic_lengths when slow, a conservative oscillator when frictionless
// (its energy, its small-amplitude period), the same equilibrium when friction damps it.

#include <algorithm>
#include <cmath>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"
#include "pamkit/effects/isotonic_motion.hpp"

using namespace pamkit_test;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// PAM 2 (the default build, the thesis bladder) with neither friction nor hysteresis nor slack:
/// its force depends on length and pressure alone, a potential force.
MuscleParams conservative() {
  MuscleParams params;
  params.friction = FrictionParams{0.0, 0.0, 0.0, 0.0, 0.0};
  return params;
}

/// The muscle's force at rest [N] at `length` under a supplied gauge `pressure_Pa`, through the
/// public static model.
double force_at_rest(const MuscleParams& params, double length, double pressure_Pa) {
  return static_forces(params, {length}, {pressure_Pa}).front();
}

std::vector<double> uniform_times(double duration, std::size_t samples) {
  std::vector<double> time(samples);
  for (std::size_t k = 0; k < samples; ++k) time[k] = duration * static_cast<double>(k) / (samples - 1.0);
  return time;
}

}  // namespace

TEST_CASE("isotonic_motion: a slow ramp follows isotonic_lengths, lagging by the friction's viscous lag",
          "[effects][isotonic_motion]") {
  // PAM 2 with its friction (Kf = 1 s/m: nearly viscous at these speeds) and pressurise/vent
  // hysteresis, 100 kPa gauge up to 400 kPa and back at 0.1 kPa/s under 100 N on 0.1 kg. A slow
  // follower lags its equilibrium by the length at which stiffness k = dF/dL takes up the
  // friction: L - L_static = -F_friction(v) / k. That is first order in tau / T (the relaxation
  // time c / k = 0.3 s against a ramp of 3000 s; the mass's m v' / k is smaller still); the
  // velocity it takes is the solver's, good to its 1e-8 m/s tolerance against at least 4.6e-6.
  // The check allows 1 % of that lag, and 1e-9 m where the lag is zero (the first sample).
  MuscleParams params;
  params.extensions.pressure_hysteresis = 0.05;
  const EffectPtr hysteresis = effect("pressure_hysteresis:coefficient=0.05");
  std::vector<double> time, pressure;
  for (int j = 0; j <= 200; ++j) {
    time.push_back(30.0 * j);
    pressure.push_back(j <= 100 ? 100e3 + 3e3 * j : 400e3 - 3e3 * (j - 100));
  }
  const double load = 100.0;
  const double mass = 0.1;
  const IsotonicLengths path = isotonic_lengths(MuscleParams{}, pressure, load, params.build.length_m, {hysteresis});
  const IsotonicMotion motion = isotonic_motion(MuscleParams{}, time, pressure, load, mass, std::nullopt, {hysteresis});
  REQUIRE(motion.length_m.size() == time.size());
  CHECK(motion.length_m.front() == path.length_m.front());  // the default start: at rest on the static path
  CHECK(motion.statistics.restarts == 1);                   // the branch flips once, after the top
  const BraidGeometry geometry(params.build);
  const std::vector<double> branch = pressure_branches(pressure);
  double largest_lag = 0.0;
  for (std::size_t j = 0; j < time.size(); ++j) {
    const double gauge = pressure[j];
    const double L = path.length_m[j];
    auto at_rest = [&](double length) {
      return detail::supplied_force(geometry, params, geometry.shape(length), gauge, 0.0, branch[j]);
    };
    const double h = 1e-7;
    const double stiffness = (at_rest(L + h) - at_rest(L - h)) / (2.0 * h);
    const double lag = -friction_force(params.friction, geometry, gauge, motion.velocity_m_per_s[j]) / stiffness;
    largest_lag = std::max(largest_lag, std::abs(lag));
    INFO("sample " << j + 1 << ", p = " << pressure[j] << " Pa, static length " << L << " m, viscous lag " << lag
                   << " m");
    CHECK(std::abs(motion.length_m[j] - L - lag) <= 0.01 * std::abs(lag) + 1e-9);
  }
  CHECK(largest_lag > 1e-6);  // the lag is there to be seen, and small against the 45 mm stroke
  CHECK(path.length_m.front() - path.length_m[100] > 0.04);
}

TEST_CASE("isotonic_motion: without friction a displaced mass conserves its energy", "[effects][isotonic_motion]") {
  // E = m v^2 / 2 + integral from the start of (F(L) - load) dL, F at rest by Gauss-Kronrod
  // quadrature of static_forces, is constant along a frictionless motion. BDF is not symplectic:
  // its energy error is what its local errors add up to, some rtol per step relative to the
  // state, twice that for a quadratic energy. The check allows 4 rtol per step, and asks that a
  // hundredfold tighter tolerance cut the drift tenfold at least (the error is the solver's,
  // not the energy's bookkeeping).
  const MuscleParams params = conservative();
  const double load = 100.0;
  const double pressure = 300e3;
  const double mass = 1.0;
  const double equilibrium = isotonic_lengths(params, {pressure}, load, params.build.length_m).length_m.front();
  const double start = equilibrium + 0.005;
  auto imbalance = [&](double length) { return force_at_rest(params, length, pressure) - load; };
  const std::vector<double> time = uniform_times(0.45, 1001);  // five periods of 0.088 s
  const std::vector<double> pressures(time.size(), pressure);
  double drift_at[2] = {0.0, 0.0};
  for (int tight = 0; tight < 2; ++tight) {
    IsotonicMotionConfig config;
    config.relative_tolerance = tight ? 1e-10 : 1e-8;
    config.absolute_tolerance_m = 1e-3 * config.relative_tolerance;
    config.absolute_tolerance_m_per_s = 1e-2 * config.relative_tolerance;
    const IsotonicMotion motion = isotonic_motion(params, time, pressures, load, mass, start, {}, config);
    double largest_kinetic = 0.0;
    double drift = 0.0;
    for (std::size_t j = 0; j < time.size(); ++j) {
      const double v = motion.velocity_m_per_s[j];
      const double potential =
          boost::math::quadrature::gauss_kronrod<double, 31>::integrate(imbalance, start, motion.length_m[j], 0);
      largest_kinetic = std::max(largest_kinetic, 0.5 * mass * v * v);
      drift = std::max(drift, std::abs(0.5 * mass * v * v + potential));
    }
    drift_at[tight] = drift / largest_kinetic;
    INFO("rtol " << config.relative_tolerance << ": energy drift " << drift_at[tight] << " of the kinetic energy "
                 << largest_kinetic << " J, " << motion.statistics.steps << " steps");
    CHECK(largest_kinetic > 0.05);  // about k A^2 / 2 = 5066 N/m (5 mm)^2 / 2
    CHECK(drift_at[tight] <= 4.0 * config.relative_tolerance * static_cast<double>(motion.statistics.steps));
  }
  CHECK(drift_at[1] <= 0.1 * drift_at[0]);
}

TEST_CASE("isotonic_motion: a small oscillation has the period 2 pi sqrt(m / k)", "[effects][isotonic_motion]") {
  // Linearised about the equilibrium, m x'' = -k x with k = dF/dL there (central difference,
  // h = 1e-6 m: truncation and rounding both below 1e-10 relative). At 10 um amplitude the
  // nonlinear shift of the frequency is of order (A F'' / F')^2 ~ (A / L)^2 ~ 1e-9; upward zero
  // crossings interpolated linearly between 200 samples a period err by (omega dt)^3 / 6 ~ 1e-6
  // of a radian at most, and alike at each crossing. The check allows 1e-6 of the period.
  const MuscleParams params = conservative();
  const double load = 100.0;
  const double pressure = 300e3;
  const double mass = 1.0;
  const double equilibrium = isotonic_lengths(params, {pressure}, load, params.build.length_m).length_m.front();
  const double h = 1e-6;
  const double stiffness =
      (force_at_rest(params, equilibrium + h, pressure) - force_at_rest(params, equilibrium - h, pressure)) / (2.0 * h);
  const double period = 2.0 * kPi * std::sqrt(mass / stiffness);
  IsotonicMotionConfig config;
  config.relative_tolerance = 1e-10;
  config.absolute_tolerance_m = 1e-14;
  config.absolute_tolerance_m_per_s = 1e-12;
  const std::vector<double> time = uniform_times(10.0 * period, 2001);
  const IsotonicMotion motion = isotonic_motion(params, time, std::vector<double>(time.size(), pressure), load, mass,
                                                equilibrium + 1e-5, {}, config);
  std::vector<double> crossings;
  for (std::size_t j = 0; j + 1 < time.size(); ++j) {
    const double before = motion.length_m[j] - equilibrium;
    const double after = motion.length_m[j + 1] - equilibrium;
    if (before < 0.0 && after >= 0.0)
      crossings.push_back(time[j] + (time[j + 1] - time[j]) * before / (before - after));
  }
  REQUIRE(crossings.size() == 10);
  const double measured = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  INFO("k = " << stiffness << " N/m");
  CHECK_REL(measured, period, 1e-6);
}

TEST_CASE("isotonic_motion: friction brings the mass to rest at isotonic_lengths's equilibrium",
          "[effects][isotonic_motion]") {
  // Displaced by 5 mm at constant pressure, the mass comes to rest where the force at rest
  // carries the load. The thesis's friction is nearly viscous here, c = 1770 N s/m at 300 kPa,
  // against 2 sqrt(k m) = 450 N s/m for critical damping: the motion is overdamped (no
  // overshoot). At a tenth of it, underdamped (it overshoots) with a decay time 2 m / c of
  // 0.11 s. After 10 s the transient is gone far below the 1e-10 m length tolerance; the check
  // allows 1e-9 m, and the force balances the load to 1e-7 (k 1e-9 m / 100 N ~ 5e-8).
  const double load = 100.0;
  const double pressure = 300e3;
  const double mass = 10.0;
  for (double friction_scale : {1.0, 0.1}) {
    MuscleParams params;
    params.friction.fiber_fiber_coefficient *= friction_scale;
    params.friction.fiber_bladder_coefficient *= friction_scale;
    const double equilibrium = isotonic_lengths(params, {pressure}, load, params.build.length_m).length_m.front();
    const std::vector<double> time = uniform_times(10.0, 1001);
    const IsotonicMotion motion =
        isotonic_motion(params, time, std::vector<double>(time.size(), pressure), load, mass, equilibrium + 0.005);
    const double overshoot = equilibrium - *std::min_element(motion.length_m.begin(), motion.length_m.end());
    INFO("friction x " << friction_scale << ", equilibrium " << equilibrium << " m, overshoot " << overshoot << " m");
    CHECK((overshoot > 1e-4) == (friction_scale < 1.0));
    CHECK(std::abs(motion.length_m.back() - equilibrium) <= 1e-9);
    CHECK(std::abs(motion.velocity_m_per_s.back()) <= 1e-9);
    CHECK_REL(motion.force_N.back(), load, 1e-7);
  }
}

TEST_CASE("isotonic_motion: a slack muscle lets its load fall freely", "[effects][isotonic_motion]") {
  // Vented (no gauge pressure, so no friction either), PAM 2's thesis bladder pushes with about
  // 20 N below 0.23 m; a braid that cannot push (braid_slack) carries nothing there, and the
  // mass falls as in a vacuum: L = L0 + (load / m) t^2 / 2. BDF integrates a quadratic exactly
  // but for its start at order 1; at rtol 1e-10 the check allows 1e-9 of the length, and of the
  // final speed.
  const double mass = 0.5;
  const double load = mass * 9.81;
  const double start = 0.17;
  const std::vector<double> time = uniform_times(0.1, 101);  // 49 mm of fall, to 0.219 m
  IsotonicMotionConfig config;
  config.relative_tolerance = 1e-10;
  config.absolute_tolerance_m = 1e-13;
  config.absolute_tolerance_m_per_s = 1e-12;
  const IsotonicMotion motion = isotonic_motion(MuscleParams{}, time, std::vector<double>(time.size(), 0.0), load, mass,
                                                start, {effect("braid_slack")}, config);
  for (std::size_t j = 0; j < time.size(); ++j) {
    INFO("t = " << time[j] << " s");
    CHECK(motion.force_N[j] == 0.0);
    CHECK(std::abs(motion.length_m[j] - start - 0.5 * 9.81 * time[j] * time[j]) <= 1e-9 * start);
    CHECK(std::abs(motion.velocity_m_per_s[j] - 9.81 * time[j]) <= 1e-9 * 9.81 * time.back());
  }
}

TEST_CASE("isotonic_motion: bad inputs are named", "[effects][isotonic_motion]") {
  using Catch::Matchers::Contains;
  const MuscleParams params;
  const std::vector<double> time{0.0, 0.5, 1.0};
  const std::vector<double> pressure{100e3, 100e3, 100e3};
  CHECK_THROWS_WITH(isotonic_motion(params, time, pressure, 100.0, 0.0), Contains("mass_kg = 0 kg"));
  CHECK_THROWS_AS(isotonic_motion(params, time, pressure, 100.0, -1.0), InvalidParameter);
  CHECK_THROWS_AS(isotonic_motion(params, time, pressure, 100.0, std::nan("")), InvalidParameter);
  CHECK_THROWS_WITH(isotonic_motion(params, time, {100e3, 100e3}, 100.0, 1.0), Contains("2 pressures for 3 times"));
  CHECK_THROWS_WITH(isotonic_motion(params, {0.0, 0.5, 0.5}, pressure, 100.0, 1.0), Contains("sample 3 has time 0.5"));
  CHECK_THROWS_WITH(isotonic_motion(params, {0.0}, {100e3}, 100.0, 1.0), Contains("two or more"));
  CHECK_THROWS_WITH(isotonic_motion(params, time, pressure, 100.0, 1.0, 0.3), Contains("start_length_m = 0.3"));
  CHECK_THROWS_AS(isotonic_motion(params, time, pressure, 100.0, 1.0, std::nullopt, {effect("sensor_lag")}),
                  InvalidParameter);
  // 2000 N is more than PAM 2 carries at 100 kPa anywhere in its braid's range: the mass pulls
  // it to the longest length the braid allows, and the run stops there, saying when and why.
  CHECK_THROWS_WITH(isotonic_motion(params, time, pressure, 2000.0, 1.0),
                    Contains("isotonic_motion: at t = ") && Contains("between samples 1 and 2") &&
                        Contains("the longest the braid allows") && Contains("outruns"));
}

TEST_CASE("isotonic_motion: Maxwell-slip elements take the energy they dissipate, and no more",
          "[effects][isotonic_motion][slip]") {
  // A displaced mass on a muscle whose only friction is Maxwell-slip (muscle/slip.hpp) rings
  // down. Its mechanical energy, m v^2 / 2 + integral of (F_elastic - load) dL + the elements'
  // spring energy, falls by exactly what the elements dissipate slipping: replayed along the
  // recorded lengths with slip_move (the motion between samples is one way but at the turns,
  // where the samples cut the slip by at most one sample's travel). The ODE's elements are states
  // of the motion: the same replay gives back the force the motion records.
  MuscleParams params = conservative();
  params.extensions.slip_force_N = 20.0;
  params.extensions.slip_distance_m = 0.002;
  MuscleParams elastic = params;
  elastic.extensions.slip_force_N = 0.0;
  const double load = 100.0;
  const double pressure = 300e3;
  const double mass = 1.0;
  const double equilibrium = isotonic_lengths(elastic, {pressure}, load, params.build.length_m).length_m.front();
  const double start = equilibrium + 0.008;
  auto imbalance = [&](double length) { return force_at_rest(elastic, length, pressure) - load; };
  const std::vector<double> time = uniform_times(0.45, 9001);
  const std::vector<double> pressures(time.size(), pressure);
  IsotonicMotionConfig config;
  config.relative_tolerance = 1e-10;
  config.absolute_tolerance_m = 1e-13;
  config.absolute_tolerance_m_per_s = 1e-12;
  const IsotonicMotion motion = isotonic_motion(params, time, pressures, load, mass, start, {}, config);
  SlipState replay;
  double dissipated = 0.0;
  double largest_energy_error = 0.0;
  const double f = params.extensions.slip_force_N;
  const double delta = params.extensions.slip_distance_m;
  const BraidGeometry geometry(params.build);
  for (std::size_t j = 0; j < time.size(); ++j) {
    if (j > 0) dissipated += slip_move(replay, f, delta, motion.length_m[j] - motion.length_m[j - 1]);
    const double v = motion.velocity_m_per_s[j];
    const double potential =
        boost::math::quadrature::gauss_kronrod<double, 31>::integrate(imbalance, start, motion.length_m[j], 0);
    const double energy = 0.5 * mass * v * v + potential + slip_stored_energy(replay, f, delta);
    largest_energy_error = std::max(largest_energy_error, std::abs(energy + dissipated));
    const double recorded_slip = motion.force_N[j] - force_at_rest(elastic, motion.length_m[j], pressure);
    INFO("sample " << j + 1);
    CHECK(std::abs(recorded_slip - replay.total_N()) <= 0.01 * f);
  }
  const double initial_energy =
      boost::math::quadrature::gauss_kronrod<double, 31>::integrate(imbalance, start, equilibrium, 0);
  INFO("dissipated " << dissipated << " J of " << -initial_energy << " J; largest energy error " << largest_energy_error
                     << " J");
  // The slip takes most of the energy; the elements that stick at the end are springs, in whose
  // stick zone the mass rings on with what is left.
  CHECK(dissipated > 0.9 * -initial_energy);
  CHECK(largest_energy_error <= 0.01 * dissipated);
  CHECK(motion.statistics.restarts > 10);  // the elements switched, each switch a restart
}
