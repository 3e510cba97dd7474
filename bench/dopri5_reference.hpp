#pragma once
/// \file
/// An explicit reference for the simulator: a thesis-style test integrated by Dormand-Prince 5(4)
/// with its dense output (Boost.Odeint's runge_kutta_dopri5) on pamkit's own right-hand side.
/// bench/bench_simulate.cpp times it as the yardstick of CVODES's bookkeeping;
/// tests/cpp/explicit_reference.test.cpp checks Simulator::run against it (one integrator against
/// another, on the same model).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "pamkit/sim/model.hpp"
#include "pamkit/sim/trajectory.hpp"

namespace pamkit_bench {

/// The channels of a run by the explicit method, and its counters.
struct Dopri5Run {
  std::vector<double> force_N, gauge_pressure_Pa, temperature_K;
  long steps = 0;
  long rhs_evaluations = 0;
};

/// The test integrated by Dormand-Prince 5(4) with its dense output, on pamkit's own right-hand
/// side as the simulator calls it (MuscleModel::evaluate_with, warm-started, the shape's
/// kinematics only) and its outputs at the samples as the simulator makes them. As the simulator
/// does, it restarts at every corner of the trajectory (its elongation rate jumps there), reads
/// each sample off the step that passed it, and evaluates the outputs with a workspace of their
/// own. A scalar tolerance pair: relative `rtol`, absolute `atol` (the simulator's temperature one).
inline Dopri5Run dopri5_run(const pamkit::MuscleModel& model, const pamkit::ElongationTrajectory& trajectory,
                            double rtol, double atol, double corner_threshold) {
  namespace odeint = boost::numeric::odeint;
  using Vector = std::array<double, pamkit::State::size>;
  const auto& time = trajectory.time();
  const auto& elongation = trajectory.elongation();
  const double initial_length = model.initial_state().length_m;
  const std::size_t n = trajectory.size();
  double largest_rate = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    largest_rate = std::max(largest_rate, std::abs(trajectory.segment_velocity(k)));
  }
  const auto corner = [&](std::size_t k) {  // the rate jumps at sample k
    return std::abs(trajectory.segment_velocity(k) - trajectory.segment_velocity(k - 1)) >
           corner_threshold * largest_rate;
  };

  Dopri5Run run;
  pamkit::MuscleWorkspace rhs_workspace, output_workspace;
  std::size_t first = 0, last = 1;  // the piece's samples
  const auto rhs = [&](const Vector& x, Vector& dxdt, double t) {
    const auto upper = std::upper_bound(time.begin() + static_cast<std::ptrdiff_t>(first),
                                        time.begin() + static_cast<std::ptrdiff_t>(last), t);
    const std::size_t k = std::clamp(static_cast<std::size_t>(upper - time.begin()), first + 1, last) - 1;
    const double velocity = trajectory.segment_velocity(k);
    pamkit::State state;
    std::copy(x.begin(), x.end(), state.values.begin());
    const pamkit::MuscleOutputs out =
        model.evaluate_with(rhs_workspace, initial_length + elongation[k] + velocity * (t - time[k]), velocity, state,
                            pamkit::ShapeParts::kinematics);
    std::copy(out.rate.values.begin(), out.rate.values.end(), dxdt.begin());
    ++run.rhs_evaluations;
  };
  const auto record = [&](std::size_t k, const Vector& x) {
    pamkit::State state;
    std::copy(x.begin(), x.end(), state.values.begin());
    const double velocity = trajectory.segment_velocity(k == 0 ? 0 : k - 1);
    const pamkit::MuscleOutputs out = model.evaluate_with(output_workspace, initial_length + elongation[k], velocity,
                                                          state, pamkit::ShapeParts::kinematics_and_braid_angle);
    run.force_N.push_back(out.forces.total);
    run.gauge_pressure_Pa.push_back(out.gauge_pressure_Pa);
    run.temperature_K.push_back(state[pamkit::State::temperature_K]);
  };

  Vector x;
  const pamkit::State initial = model.initial();
  std::copy(initial.values.begin(), initial.values.end(), x.begin());
  record(0, x);
  auto stepper = odeint::make_dense_output(atol, rtol, odeint::runge_kutta_dopri5<Vector>());
  double step = 1e-3 * (time[1] - time[0]);
  while (first + 1 < n) {
    last = first + 1;
    while (last + 1 < n && !corner(last)) ++last;
    stepper.initialize(x, time[first], step);
    for (std::size_t k = first + 1; k <= last;) {
      while (stepper.current_time() < time[k]) {
        stepper.do_step(rhs);
        ++run.steps;
      }
      for (; k <= last && time[k] <= stepper.current_time(); ++k) {
        stepper.calc_state(time[k], x);
        record(k, x);
      }
    }
    step = stepper.current_time_step();
    first = last;  // x is the state at the piece's end, its last sample's
  }
  return run;
}

}  // namespace pamkit_bench
