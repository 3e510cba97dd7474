// CVODES glue for pamkit::Simulator: the trajectory integrated piece by piece between its
// corners, one CVODES step per call, the samples interpolated, by BDF or Adams as the
// configuration or the stiffness test says; with the handles and flag checks of cvodes_support.hpp.

#include "pamkit/sim/simulator.hpp"

#include <nvector/nvector_serial.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <memory>
#include <type_traits>
#include <vector>

#include "cvodes_support.hpp"

namespace pamkit {
namespace {

using cvodes::add_statistics;
using cvodes::check_flag;

State to_state(N_Vector v) {
  State s;
  std::copy(NV_DATA_S(v), NV_DATA_S(v) + State::size, s.values.begin());
  return s;
}

/// Per-run mutable workspace handed to CVODES as user data.
struct RunWorkspace {
  const MuscleModel& model;
  const ElongationTrajectory& trajectory;
  std::size_t piece_start;   // first sample of the piece being integrated
  std::size_t piece_end;     // its last sample
  std::exception_ptr error;  // an exception thrown inside the callback, rethrown after CVode returns
  MuscleWorkspace rhs;       // the right-hand side's warm start: CVODES calls it at nearby lengths
  MuscleWorkspace output;    // the samples' own, which run behind CVODES's steps

  /// The segment [t_k, t_k+1] of the piece that holds time t (CVODES may step past samples).
  std::size_t segment(double t) const {
    const auto& time = trajectory.time();
    const auto first = time.begin() + static_cast<std::ptrdiff_t>(piece_start);
    const auto last = time.begin() + static_cast<std::ptrdiff_t>(piece_end);
    const auto upper = std::upper_bound(first, last, t);
    const std::size_t k = static_cast<std::size_t>(upper - time.begin());
    return std::clamp(k == 0 ? 0 : k - 1, piece_start, piece_end - 1);
  }
  double length(double t, std::size_t k) const {
    return model.initial_state().length_m + trajectory.elongation()[k] +
           trajectory.segment_velocity(k) * (t - trajectory.time()[k]);
  }
};

int muscle_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
  auto& w = *static_cast<RunWorkspace*>(user_data);
  try {
    const std::size_t k = w.segment(t);
    const MuscleOutputs out = w.model.evaluate_with(w.rhs, w.length(t, k), w.trajectory.segment_velocity(k),
                                                    to_state(y), ShapeParts::kinematics);
    std::copy(out.rate.values.begin(), out.rate.values.end(), NV_DATA_S(ydot));
    return 0;
  } catch (...) {
    w.error = std::current_exception();
    return -1;  // unrecoverable: CVode returns CV_RHSFUNC_FAIL and run() rethrows
  }
}

/// True where the elongation rate jumps by more than `threshold`: a turning point or the start
/// of a hold, where CVODES restarts. Smaller changes (a sampled curve, encoder noise on a
/// measured crosshead) are integrated through: the length stays continuous and the error
/// test sees the kink.
bool is_corner(double previous_velocity, double velocity, double threshold) {
  return std::abs(velocity - previous_velocity) > threshold;
}

/// The rate jump that makes a corner: `config.corner_threshold` of the trajectory's largest rate.
double corner_jump(const ElongationTrajectory& trajectory, const SimulatorConfig& config) {
  double largest_rate = 0.0;
  for (std::size_t k = 0; k + 1 < trajectory.size(); ++k) {
    largest_rate = std::max(largest_rate, std::abs(trajectory.segment_velocity(k)));
  }
  return config.corner_threshold * largest_rate;
}

/// The last sample of the piece that starts at sample `k`: the next corner, or the end.
std::size_t piece_end(const ElongationTrajectory& trajectory, std::size_t k, double corner) {
  std::size_t end = k + 1;
  while (end + 1 < trajectory.size() &&
         !is_corner(trajectory.segment_velocity(end - 1), trajectory.segment_velocity(end), corner)) {
    ++end;
  }
  return end;
}

/// Every output column of a result (all but the prescribed time and elongation); `Result` is
/// SimulationResult or const SimulationResult.
template <class Result>
auto outputs(Result& r) {
  using Column = std::conditional_t<std::is_const_v<Result>, const std::vector<double>, std::vector<double>>;
  return std::array<Column*, 12>{&r.length_m,      &r.force_N,       &r.friction_force_N, &r.pressure_gauge_Pa,
                                 &r.temperature_K, &r.gas_volume_m3, &r.gas_mass_kg,      &r.braid_angle_rad,
                                 &r.diameter_m,    &r.work_J,        &r.heat_lost_J,      &r.friction_dissipated_J};
}

/// Collects samples, recorded in order, into blocks of a SimulationResult and hands each full
/// block to the sink.
class BlockRecorder {
 public:
  /// `shapes`: the samples' braid shapes, or null to solve them (a table that applies to the run).
  BlockRecorder(const ElongationTrajectory& trajectory, std::size_t block_size, const SampleSink& sink,
                const ShapeTable* shapes)
      : trajectory_(trajectory), block_size_(block_size), sink_(sink), shapes_(shapes) {
    start_block();
  }

  /// Records sample `k` (the one after the last recorded): one model evaluation at the state
  /// CVODES reports for its time, at the tabulated shape if there is a table.
  void record(std::size_t k, const MuscleModel& model, MuscleWorkspace& workspace, double velocity, const State& y,
              SolverStatistics& statistics) {
    const std::size_t i = k - first_;
    const double length = model.initial_state().length_m + block_.elongation_m[i];
    const MuscleOutputs out =
        shapes_ ? model.evaluate_at_shape(shapes_->shape(k), velocity, y)
                : model.evaluate_with(workspace, length, velocity, y, ShapeParts::kinematics_and_braid_angle);
    ++statistics.output_evaluations;
    if (shapes_) ++statistics.tabulated_shapes;
    block_.length_m[i] = length;
    block_.force_N[i] = out.forces.total;
    block_.friction_force_N[i] = out.forces.friction;
    block_.pressure_gauge_Pa[i] = out.gauge_pressure_Pa;
    block_.temperature_K[i] = y[State::temperature_K];
    block_.gas_volume_m3[i] = out.gas_volume_m3;
    block_.gas_mass_kg[i] = y[State::gas_mass_kg];
    block_.braid_angle_rad[i] = out.shape.braid_angle;
    block_.diameter_m[i] = out.shape.diameter;
    block_.work_J[i] = y[State::work_J];
    block_.heat_lost_J[i] = y[State::heat_lost_J];
    block_.friction_dissipated_J[i] = y[State::friction_dissipated_J];
    if (i + 1 == block_.time_s.size()) {
      sink_(first_, block_);
      first_ += block_.time_s.size();
      if (first_ < trajectory_.size()) start_block();
    }
  }

 private:
  /// Sizes the block for the samples from first_, the prescribed columns filled.
  void start_block() {
    const std::size_t n = std::min(block_size_, trajectory_.size() - first_);
    const auto from = static_cast<std::ptrdiff_t>(first_);
    const auto to = static_cast<std::ptrdiff_t>(first_ + n);
    block_.time_s.assign(trajectory_.time().begin() + from, trajectory_.time().begin() + to);
    block_.elongation_m.assign(trajectory_.elongation().begin() + from, trajectory_.elongation().begin() + to);
    for (std::vector<double>* column : outputs(block_)) column->resize(n);
  }

  const ElongationTrajectory& trajectory_;
  std::size_t block_size_;
  const SampleSink& sink_;
  const ShapeTable* shapes_;
  std::size_t first_ = 0;
  SimulationResult block_;
};

/// Samples per block when run() collects a whole result.
constexpr std::size_t kCollectBlockSize = 4096;

}  // namespace

StiffnessEstimate estimate_stiffness(const MuscleModel& model, const ElongationTrajectory& trajectory,
                                     const SimulatorConfig& config) {
  config.validate();
  const auto& time = trajectory.time();
  const double corner = corner_jump(trajectory, config);
  double longest = 0.0;
  for (std::size_t k = 0; k + 1 < trajectory.size();) {
    const std::size_t end = piece_end(trajectory, k, corner);
    longest = std::max(longest, time[end] - time[k]);
    k = end;
  }
  // Inside a piece the motion is smooth on the piece's own time scale, so a method of order q
  // meets the tolerance with steps of about that scale times rtol^(1/(q+1)); q = 5, BDF's
  // highest order, is the smaller step of the two methods (Adams goes to 12).
  double step = longest * std::pow(config.relative_tolerance, 1.0 / 6.0);
  if (config.max_step_s > 0.0) step = std::min(step, config.max_step_s);
  return StiffnessEstimate{model.fastest_rate_per_s(), longest, step};
}

Simulator::Simulator(SimulatorConfig config) : config_(config) { config_.validate(); }

SimulationResult Simulator::run(const MuscleModel& model, const ElongationTrajectory& trajectory,
                                const ShapeTable* shapes) const {
  SimulationResult result;
  result.time_s = trajectory.time();
  result.elongation_m = trajectory.elongation();
  for (std::vector<double>* column : outputs(result)) column->resize(trajectory.size());
  result.statistics = run_blocks(
      model, trajectory, kCollectBlockSize,
      [&result](std::size_t first, const SimulationResult& block) {
        const auto at = static_cast<std::ptrdiff_t>(first);
        const auto from = outputs(block);
        const auto to = outputs(result);
        for (std::size_t c = 0; c < from.size(); ++c) std::copy(from[c]->begin(), from[c]->end(), to[c]->begin() + at);
      },
      shapes);
  return result;
}

SolverStatistics Simulator::run_blocks(const MuscleModel& model, const ElongationTrajectory& trajectory,
                                       std::size_t block_size, const SampleSink& sink, const ShapeTable* shapes) const {
  if (block_size == 0) throw InvalidInput("Simulator.run_blocks: block_size must be at least 1");
  const auto& time = trajectory.time();
  const auto& elongation = trajectory.elongation();
  const BraidGeometry& geometry = model.geometry();
  for (std::size_t k = 0; k < trajectory.size(); ++k) {
    const double length = model.initial_state().length_m + elongation[k];
    if (!(length > geometry.min_length() && length < geometry.max_length())) {
      throw InvalidInput(detail::message("trajectory sample ", k, " (t = ", time[k], " s, elongation ", elongation[k],
                                         " m) gives muscle length ", length, " m, outside the braid's range (",
                                         geometry.min_length(), ", ", geometry.max_length(),
                                         ") m: check the elongation's zero (it is the stretch from the length at the "
                                         "start of the test) and [test] initial_length_m"));
    }
  }

  auto context = cvodes::make_context();
  SUNContext ctx = *context;
  cvodes::Vector y(N_VNew_Serial(State::size, ctx));
  cvodes::Vector tolerances(N_VNew_Serial(State::size, ctx));
  cvodes::Vector sample_state(N_VNew_Serial(State::size, ctx));  // CVODES's interpolant at a sample
  if (!y || !tolerances || !sample_state) throw SolverError("N_VNew_Serial failed");
  const State initial = model.initial();
  std::copy(initial.values.begin(), initial.values.end(), NV_DATA_S(y.get()));
  // Absolute tolerances by each state's scale: the temperature's, relative to the ambient
  // temperature, carried over to the gas mass and to stresses of order 1 MPa.
  const double relative = config_.absolute_tolerance_K / model.initial_temperature();
  NV_Ith_S(tolerances.get(), State::temperature_K) = config_.absolute_tolerance_K;
  NV_Ith_S(tolerances.get(), State::gas_mass_kg) = relative * model.gas_mass();
  NV_Ith_S(tolerances.get(), State::viscous_stress_l_Pa) = relative * 1e6;
  NV_Ith_S(tolerances.get(), State::viscous_stress_h_Pa) = relative * 1e6;
  for (int i : {State::work_J, State::heat_lost_J, State::friction_dissipated_J}) {
    NV_Ith_S(tolerances.get(), i) = config_.absolute_tolerance_J;
  }

  RunWorkspace workspace{model, trajectory, 0, 1, nullptr, {}, {}};
  const double t0 = time.front();
  IntegrationMethod method = config_.method;
  if (method == IntegrationMethod::automatic) {
    method = estimate_stiffness(model, trajectory, config_).stiff() ? IntegrationMethod::bdf : IntegrationMethod::adams;
  }
  const cvodes::Solver solver =
      cvodes::make_solver(method, ctx, muscle_rhs, t0, y.get(), &workspace, config_.relative_tolerance,
                          tolerances.get(), config_.max_steps, config_.max_step_s);
  void* cv = solver.get();

  SolverStatistics statistics;
  // A table for another build, other lengths or compliant fibers is left alone: the shapes are
  // then solved as without one.
  const ShapeTable* tabulated = shapes && shapes->applies_to(model, trajectory) ? shapes : nullptr;
  BlockRecorder recorder(trajectory, block_size, sink, tabulated);
  recorder.record(0, model, workspace.output, trajectory.segment_velocity(0), initial, statistics);

  // Integrate piece by piece between corners, where the elongation rate jumps: CVODES stops
  // exactly there (its stop time) and restarts its BDF history. Inside a piece it takes one
  // step per call, and every sample the step passed is read off its interpolating polynomial
  // (CVodeGetDky, which CV_NORMAL mode uses too): one call per step, not per sample, and the
  // samples do not steer the steps.
  const double corner = corner_jump(trajectory, config_);
  double t = t0;
  std::size_t k = 0;
  while (k + 1 < trajectory.size()) {
    const std::size_t end = piece_end(trajectory, k, corner);
    workspace.piece_start = k;
    workspace.piece_end = end;
    if (k > 0) {
      add_statistics(solver, statistics);
      check_flag(CVodeReInit(cv, t, y.get()), "CVodeReInit", t);
      ++statistics.restarts;
    }
    check_flag(CVodeSetStopTime(cv, time[end]), "CVodeSetStopTime", t);
    std::size_t sample = k + 1;
    double steps_since_sample = 0;
    while (sample <= end) {
      while (t < time[sample]) {
        // CVODES counts its mxstep per call; one step per call, the simulator counts them.
        if (++steps_since_sample > config_.max_steps) {
          throw SolverError(detail::message("CVode failed with CV_TOO_MUCH_WORK at t = ", t, " s: more than ",
                                            config_.max_steps, " steps before the sample at t = ", time[sample],
                                            " s (SimulatorConfig.max_steps)"));
        }
        // The output time only sizes the first step after a (re)start: the piece's end, so the
        // samples leave the step sequence alone.
        const int flag = CVode(cv, time[end], y.get(), &t, CV_ONE_STEP);
        if (workspace.error) std::rethrow_exception(workspace.error);
        check_flag(flag, "CVode", t);
      }
      for (; sample <= end && time[sample] <= t; ++sample) {
        check_flag(CVodeGetDky(cv, time[sample], 0, sample_state.get()), "CVodeGetDky", time[sample]);
        recorder.record(sample, model, workspace.output, trajectory.segment_velocity(sample - 1),
                        to_state(sample_state.get()), statistics);
        steps_since_sample = 0;
      }
    }
    k = end;
  }
  add_statistics(solver, statistics);
  return statistics;
}

}  // namespace pamkit
