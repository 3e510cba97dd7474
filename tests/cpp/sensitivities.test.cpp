// Simulator::run_sensitivities: the forward sensitivities CVODES integrates beside the state,
// checked against a closed form, against central differences of two tightly integrated runs,
// and the nominal run against the plain run.

#include <algorithm>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "pamkit/sim/simulator.hpp"

namespace {

using namespace pamkit;

constexpr double kStep = 1e-6;

/// Table C.2's test with a gas that exchanges heat in `tau` s; pressure, friction and tau scaled.
MuscleModel muscle(double pressure_scale = 1.0, double friction_scale = 1.0, double tau = 2.0) {
  MuscleParams p;
  p.gas.process = GasProcess::heat_transfer;
  p.gas.heat_transfer_time_constant_s = tau;
  p.friction.fiber_fiber_coefficient *= friction_scale;
  p.friction.fiber_bladder_coefficient *= friction_scale;
  return MuscleModel(p, InitialState{0.167, 236.63e3 * pressure_scale});
}

Simulator simulator(double tolerance) {
  SimulatorConfig config;
  config.relative_tolerance = tolerance;
  config.absolute_tolerance_K = tolerance;
  return Simulator(config);
}

double largest(const std::vector<double>& v) {
  double out = 0.0;
  for (double x : v) out = std::max(out, std::abs(x));
  return out;
}

/// Largest |a - b| over the largest |b|.
double relative_gap(const std::vector<double>& a, const std::vector<double>& b) {
  double gap = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) gap = std::max(gap, std::abs(a[k] - b[k]));
  return gap / largest(b);
}

}  // namespace

TEST_CASE("run_sensitivities: the pressure's sensitivity to the initial pressure is the closed form",
          "[sim][sensitivities]") {
  // The sealed gas's mass is proportional to the initial absolute pressure and its temperature
  // does not depend on the mass (the heat exchange is per unit mass), so p_abs(t) scales with
  // p_abs(0): d p(t) / d p(0) = p_abs(t) / p_abs(0), at every sample.
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 2);
  const MuscleModel nominal = muscle();
  const double h = kStep * 236.63e3;  // per pascal of initial pressure
  const SensitivityResult r = simulator(1e-8).run_sensitivities(nominal, {muscle(1.0 + kStep)}, {h}, trajectory);
  const double atmosphere = nominal.params().gas.atmospheric_pressure_Pa;
  const double initial_absolute = atmosphere + 236.63e3;
  std::vector<double> closed_form;
  for (double gauge : r.run.gauge_pressure_Pa) closed_form.push_back((gauge + atmosphere) / initial_absolute);
  CHECK(relative_gap(r.derivatives[0].gauge_pressure_Pa, closed_form) < 1e-6);
  // The temperature does not depend on it: its sensitivity stays at the noise of the quotient.
  CHECK(largest(r.derivatives[0].temperature_K) < 1e-6);
}

TEST_CASE("run_sensitivities: agree with central differences of tightly integrated runs", "[sim][sensitivities]") {
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 2);
  const SensitivityResult r = simulator(1e-8).run_sensitivities(
      muscle(), {muscle(1.0, 1.0 + kStep), muscle(1.0, 1.0, 2.0 + kStep)}, {kStep, kStep}, trajectory);
  // Central differences of runs at rtol 1e-11, a step of 1e-4: truncation ~1e-8, the runs'
  // own error ~1e-11 / 1e-4 = 1e-7 of the slope.
  const Simulator tight = simulator(1e-11);
  const double d = 1e-4;
  const SimulationResult friction_up = tight.run(muscle(1.0, 1.0 + d), trajectory);
  const SimulationResult friction_down = tight.run(muscle(1.0, 1.0 - d), trajectory);
  const SimulationResult tau_up = tight.run(muscle(1.0, 1.0, 2.0 + d), trajectory);
  const SimulationResult tau_down = tight.run(muscle(1.0, 1.0, 2.0 - d), trajectory);
  const auto central = [d](const std::vector<double>& up, const std::vector<double>& down) {
    std::vector<double> out(up.size());
    for (std::size_t k = 0; k < up.size(); ++k) out[k] = (up[k] - down[k]) / (2.0 * d);
    return out;
  };
  // Tolerances: measured 2e-7 (friction, which the gas does not feel) and 3e-5 (tau, through the
  // integrated temperature at rtol 1e-8, the sensitivities outside the error test).
  CHECK(relative_gap(r.derivatives[0].force_N, central(friction_up.force_N, friction_down.force_N)) < 1e-6);
  CHECK(largest(r.derivatives[0].gauge_pressure_Pa) == 0.0);
  CHECK(relative_gap(r.derivatives[1].force_N, central(tau_up.force_N, tau_down.force_N)) < 1e-4);
  CHECK(relative_gap(r.derivatives[1].gauge_pressure_Pa,
                     central(tau_up.gauge_pressure_Pa, tau_down.gauge_pressure_Pa)) < 1e-4);
  CHECK(relative_gap(r.derivatives[1].temperature_K, central(tau_up.temperature_K, tau_down.temperature_K)) < 1e-4);
  CHECK(r.run.statistics.sensitivity_rhs_evaluations > 0);
}

/// `trajectory` with every elongation multiplied by `scale` (a crosshead whose travel reads off by a factor).
ElongationTrajectory scaled(const ElongationTrajectory& trajectory, double scale) {
  std::vector<double> elongation = trajectory.elongation();
  for (double& e : elongation) e *= scale;
  return ElongationTrajectory(trajectory.time(), elongation);
}

TEST_CASE("run_sensitivities: a parameter that moves the muscle's motion, against central differences",
          "[sim][sensitivities]") {
  // A travel scale moves the muscle off the trajectory (as a fixture's slack does), keeping its
  // corners: the moved model is the nominal one along the scaled motion.
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 2);
  const SensitivityResult r = simulator(1e-8).run_sensitivities(muscle(), {muscle()}, {kStep}, trajectory, nullptr,
                                                                {scaled(trajectory, 1.0 + kStep)});
  const Simulator tight = simulator(1e-11);
  const double d = 1e-4;
  const SimulationResult up = tight.run(muscle(), scaled(trajectory, 1.0 + d));
  const SimulationResult down = tight.run(muscle(), scaled(trajectory, 1.0 - d));
  const auto central = [d](const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> out(a.size());
    for (std::size_t k = 0; k < a.size(); ++k) out[k] = (a[k] - b[k]) / (2.0 * d);
    return out;
  };
  // As for the heat time constant above: the slope through the integrated gas state at rtol
  // 1e-8, the sensitivities outside the error test.
  CHECK(relative_gap(r.derivatives[0].force_N, central(up.force_N, down.force_N)) < 1e-4);
  CHECK(relative_gap(r.derivatives[0].gauge_pressure_Pa, central(up.gauge_pressure_Pa, down.gauge_pressure_Pa)) < 1e-4);
  CHECK(relative_gap(r.derivatives[0].temperature_K, central(up.temperature_K, down.temperature_K)) < 1e-4);
  // The motion's own derivative is the elongation itself (d(s e)/ds), to the quotient's rounding.
  CHECK(relative_gap(r.derivatives[0].elongation_m, trajectory.elongation()) < 1e-8);
}

TEST_CASE("run_sensitivities: the run beside the sensitivities is the plain run's, to its tolerance",
          "[sim][sensitivities]") {
  // The sensitivities ride on the state's steps, outside the error test: the run differs from a
  // plain one only by the Newton iterations' rounding (a fit's residual and Jacobian see one
  // model). Measured: 5e-14 of a channel's range at rtol 1e-6, rounding.
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 2);
  const Simulator s = simulator(1e-6);
  const SimulationResult plain = s.run(muscle(), trajectory);
  const SensitivityResult r = s.run_sensitivities(muscle(), {muscle(1.0 + kStep)}, {kStep}, trajectory);
  CHECK(relative_gap(r.run.force_N, plain.force_N) < 1e-12);
  CHECK(relative_gap(r.run.gauge_pressure_Pa, plain.gauge_pressure_Pa) < 1e-12);
  CHECK(relative_gap(r.run.temperature_K, plain.temperature_K) < 1e-12);
  CHECK(r.run.statistics.steps == plain.statistics.steps);
}

TEST_CASE("run_sensitivities: derivatives at the rows asked for are those of every row, NaN elsewhere",
          "[sim][sensitivities]") {
  // Every third sample: a moved model's braid closure then starts from the sample read three
  // before, so the derivatives agree to the closure's tolerance over the step, not to the bit.
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 2);
  const Simulator s = simulator(1e-8);
  const std::vector<MuscleModel> moved{muscle(1.0 + kStep), muscle(1.0, 1.0, 2.0 + kStep)};
  const SensitivityResult every = s.run_sensitivities(muscle(), moved, {kStep, kStep}, trajectory);
  std::vector<std::size_t> rows;
  for (std::size_t k = 1; k < trajectory.size(); k += 3) rows.push_back(k);
  const SensitivityResult some = s.run_sensitivities(muscle(), moved, {kStep, kStep}, trajectory, nullptr, {}, rows);
  for (std::size_t i = 0; i < moved.size(); ++i) {
    const SimulationResult& a = every.derivatives[i];
    const SimulationResult& b = some.derivatives[i];
    std::vector<double> at_rows_a, at_rows_b;
    for (std::size_t k : rows) {
      at_rows_a.push_back(a.force_N[k]);
      at_rows_b.push_back(b.force_N[k]);
      CHECK(b.temperature_K[k] == a.temperature_K[k]);  // the state's sensitivity: no closure in it
    }
    // Boost's Newton iteration stops within 2^-45 (3e-14) of a diameter, which the force
    // amplifies and the quotient divides by its 1e-6 step: the derivatives' own accuracy, ~1e-6
    // relative (docs), which reading fewer rows must keep. Measured: 1.3e-7.
    CHECK(relative_gap(at_rows_b, at_rows_a) < 1e-6);
    CHECK(std::isnan(b.force_N[0]));
    CHECK(std::isnan(b.gauge_pressure_Pa[2]));
  }
  // The nominal run is whole and the same; a third of the moved models' outputs are evaluated.
  CHECK(some.run.force_N == every.run.force_N);
  const long nominal = static_cast<long>(trajectory.size());
  CHECK(every.run.statistics.output_evaluations == nominal * 3);
  CHECK(some.run.statistics.output_evaluations == nominal + 2 * static_cast<long>(rows.size()));
}

TEST_CASE("run_sensitivities: refuses mismatched sizes and zero steps", "[sim][sensitivities]") {
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 1);
  const Simulator s;
  CHECK_THROWS_AS(s.run_sensitivities(muscle(), {muscle(1.1)}, {}, trajectory), InvalidInput);
  CHECK_THROWS_WITH(s.run_sensitivities(muscle(), {muscle(1.1)}, {0.0}, trajectory), Catch::Contains("step 0 is 0"));
  CHECK_THROWS_WITH(s.run_sensitivities(muscle(), {muscle(1.1)}, {0.1}, trajectory, nullptr, {trajectory, trajectory}),
                    Catch::Contains("2 moved motions for 1 moved models"));
  std::vector<double> later = trajectory.time();
  for (double& t : later) t += 1.0;
  CHECK_THROWS_WITH(s.run_sensitivities(muscle(), {muscle(1.1)}, {0.1}, trajectory, nullptr,
                                        {ElongationTrajectory(later, trajectory.elongation())}),
                    Catch::Contains("moved motion 0 is not sampled at the trajectory's times"));
  CHECK_THROWS_WITH(s.run_sensitivities(muscle(), {muscle(1.1)}, {0.1}, trajectory, nullptr, {}, {3, 3}),
                    Catch::Contains("rows[1] = 3 does not increase (rows[0] = 3)"));
  CHECK_THROWS_WITH(s.run_sensitivities(muscle(), {muscle(1.1)}, {0.1}, trajectory, nullptr, {}, {trajectory.size()}),
                    Catch::Contains("is past the trajectory's last sample"));
}
