// CVODES glue for pamkit::Simulator: the trajectory integrated piece by piece between its
// corners, one CVODES step per call, the samples interpolated, by BDF or Adams as the
// configuration or the stiffness test says; with the handles and flag checks of cvodes_support.hpp.

#include "pamkit/sim/simulator.hpp"

#include <nvector/nvector_serial.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <type_traits>
#include <vector>

#include <boost/numeric/odeint.hpp>

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

/// The moved models of a run with sensitivities (Simulator::run_sensitivities), each with its
/// own motion and warm starts, and the counters of their evaluations.
struct MovedModels {
  const std::vector<MuscleModel>& models;
  const std::vector<double>& steps;
  std::vector<const ElongationTrajectory*> motions;  // per moved model: its own, or the run's trajectory
  std::vector<MuscleWorkspace> rhs;
  std::vector<MuscleWorkspace> output;
  std::vector<const ShapeTable*> shapes;  // per moved model: the table where it applies, else null
  std::vector<char> wanted;               // per sample: whether its derivatives are read (empty: every one)
  long rhs_evaluations = 0;

  /// Whether the derivatives at sample k are read (run_sensitivities' `rows`).
  bool wants(std::size_t k) const { return wanted.empty() || wanted[k]; }
};

/// Per-run mutable workspace handed to CVODES as user data.
struct RunWorkspace {
  const MuscleModel& model;
  const ElongationTrajectory& trajectory;
  std::size_t piece_start;   // first sample of the piece being integrated
  std::size_t piece_end;     // its last sample
  std::exception_ptr error;  // an exception thrown inside the callback, rethrown after CVode returns
  MuscleWorkspace rhs;       // the right-hand side's warm start: CVODES calls it at nearby lengths
  MuscleWorkspace output;    // the samples' own, which run behind CVODES's steps
  MovedModels* moved;        // null without sensitivities

  /// The segment [t_k, t_k+1] of the piece that holds time t (CVODES may step past samples).
  std::size_t segment(double t) const {
    const auto& time = trajectory.time();
    const auto first = time.begin() + static_cast<std::ptrdiff_t>(piece_start);
    const auto last = time.begin() + static_cast<std::ptrdiff_t>(piece_end);
    const auto upper = std::upper_bound(first, last, t);
    const std::size_t k = static_cast<std::size_t>(upper - time.begin());
    return std::clamp(k == 0 ? 0 : k - 1, piece_start, piece_end - 1);
  }
  /// The length of `m` (the model or a moved one, each from its own initial length) along
  /// `motion` (the trajectory or a moved motion on its times) at time t in segment k.
  static double length(const MuscleModel& m, const ElongationTrajectory& motion, double t, std::size_t k) {
    return m.initial_state().length_m + motion.elongation()[k] + motion.segment_velocity(k) * (t - motion.time()[k]);
  }
};

/// y + h s: the state a moved model is evaluated at, s a sensitivity.
State shifted(const State& y, double h, N_Vector s) {
  State out = y;
  for (int j = 0; j < State::size; ++j) out[j] += h * NV_Ith_S(s, j);
  return out;
}

int muscle_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
  auto& w = *static_cast<RunWorkspace*>(user_data);
  try {
    const std::size_t k = w.segment(t);
    const MuscleOutputs out =
        w.model.evaluate_with(w.rhs, RunWorkspace::length(w.model, w.trajectory, t, k),
                              w.trajectory.segment_velocity(k), to_state(y), ShapeParts::kinematics);
    std::copy(out.rate.values.begin(), out.rate.values.end(), NV_DATA_S(ydot));
    return 0;
  } catch (...) {
    w.error = std::current_exception();
    return -1;  // unrecoverable: CVode returns CV_RHSFUNC_FAIL and run() rethrows
  }
}

/// The sensitivities' right-hand sides, s_i' = (f_i(t, y + h_i s_i) - f(t, y)) / h_i with f_i the
/// moved model i: the directional difference quotient CVODES forms for parameters it holds.
int sensitivity_rhs(int count, sunrealtype t, N_Vector y, N_Vector ydot, N_Vector* yS, N_Vector* ySdot, void* user_data,
                    N_Vector, N_Vector) {
  auto& w = *static_cast<RunWorkspace*>(user_data);
  try {
    const std::size_t k = w.segment(t);
    const State state = to_state(y);
    MovedModels& moved = *w.moved;
    for (int i = 0; i < count; ++i) {
      const auto m = static_cast<std::size_t>(i);
      const double h = moved.steps[m];
      const MuscleModel& model = moved.models[m];
      const ElongationTrajectory& motion = *moved.motions[m];
      const MuscleOutputs out =
          model.evaluate_with(moved.rhs[m], RunWorkspace::length(model, motion, t, k), motion.segment_velocity(k),
                              shifted(state, h, yS[i]), ShapeParts::kinematics);
      for (int j = 0; j < State::size; ++j) NV_Ith_S(ySdot[i], j) = (out.rate[j] - NV_Ith_S(ydot, j)) / h;
    }
    moved.rhs_evaluations += count;
    return 0;
  } catch (...) {
    w.error = std::current_exception();
    return -1;
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
  std::array<Column*, 12> columns{};
  std::size_t next = 0;
  SimulationResult::for_each_column(
      [&](const char*, std::vector<double> SimulationResult::*member, const char*, const char*, bool output) {
        if (output) columns.at(next++) = &(r.*member);
      });
  return columns;
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
  /// \returns the model's outputs there.
  MuscleOutputs record(std::size_t k, const MuscleModel& model, MuscleWorkspace& workspace, double velocity,
                       const State& y, SolverStatistics& statistics) {
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
    block_.gauge_pressure_Pa[i] = out.gauge_pressure_Pa;
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
    return out;
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

/// Differentiates each sample's outputs into SensitivityResult::derivatives: output j of moved
/// model i (along its own motion) at y + h_i s_i less the nominal's, over h_i.
class DerivativeRecorder {
 public:
  /// `nominal_length_m`: the nominal model's initial length, which a moved one may differ from.
  DerivativeRecorder(MovedModels& moved, const ElongationTrajectory& trajectory, double nominal_length_m,
                     std::vector<SimulationResult>& derivatives)
      : moved_(moved), nominal_length_(nominal_length_m), derivatives_(derivatives) {
    derivatives_.resize(moved.models.size());
    for (std::size_t i = 0; i < derivatives_.size(); ++i) {
      SimulationResult& d = derivatives_[i];
      d.time_s = trajectory.time();
      d.elongation_m.resize(trajectory.size());
      const std::vector<double>& motion = moved.motions[i]->elongation();
      for (std::size_t k = 0; k < trajectory.size(); ++k) {
        d.elongation_m[k] = (motion[k] - trajectory.elongation()[k]) / moved.steps[i];
      }
      // NaN where a sample is not read: a caller that reads it anyway sees it.
      for (std::vector<double>* column : outputs(d)) {
        column->assign(trajectory.size(), std::numeric_limits<double>::quiet_NaN());
      }
    }
  }

  /// Whether sample k's derivatives are recorded (run_sensitivities' `rows`).
  bool wants(std::size_t k) const { return moved_.wants(k); }

  /// Sample k, whose friction reads the elongation rate of segment `segment` (k - 1, or 0 at the
  /// start); nothing where the sample is not wanted, whose sensitivities `yS` were not read.
  void record(std::size_t k, std::size_t segment, const State& y, N_Vector* yS, const MuscleOutputs& nominal,
              SolverStatistics& statistics) {
    if (!wants(k)) return;
    for (std::size_t i = 0; i < derivatives_.size(); ++i) {
      const double h = moved_.steps[i];
      const MuscleModel& model = moved_.models[i];
      const ElongationTrajectory& motion = *moved_.motions[i];
      const double velocity = motion.segment_velocity(segment);
      const State y_moved = shifted(y, h, yS[i]);
      const double length = model.initial_state().length_m + motion.elongation()[k];
      const MuscleOutputs out = moved_.shapes[i]
                                    ? model.evaluate_at_shape(moved_.shapes[i]->shape(k), velocity, y_moved)
                                    : model.evaluate_with(moved_.output[i], length, velocity, y_moved,
                                                          ShapeParts::kinematics_and_braid_angle);
      ++statistics.output_evaluations;
      if (moved_.shapes[i]) ++statistics.tabulated_shapes;
      SimulationResult& d = derivatives_[i];
      const auto slope = [h](double moved, double base) { return (moved - base) / h; };
      d.length_m[k] = slope(model.initial_state().length_m, nominal_length_);
      d.force_N[k] = slope(out.forces.total, nominal.forces.total);
      d.friction_force_N[k] = slope(out.forces.friction, nominal.forces.friction);
      d.gauge_pressure_Pa[k] = slope(out.gauge_pressure_Pa, nominal.gauge_pressure_Pa);
      d.temperature_K[k] = NV_Ith_S(yS[i], State::temperature_K);
      d.gas_volume_m3[k] = slope(out.gas_volume_m3, nominal.gas_volume_m3);
      d.gas_mass_kg[k] = NV_Ith_S(yS[i], State::gas_mass_kg);
      d.braid_angle_rad[k] = slope(out.shape.braid_angle, nominal.shape.braid_angle);
      d.diameter_m[k] = slope(out.shape.diameter, nominal.shape.diameter);
      d.work_J[k] = NV_Ith_S(yS[i], State::work_J);
      d.heat_lost_J[k] = NV_Ith_S(yS[i], State::heat_lost_J);
      d.friction_dissipated_J[k] = NV_Ith_S(yS[i], State::friction_dissipated_J);
    }
  }

 private:
  MovedModels& moved_;
  double nominal_length_;
  std::vector<SimulationResult>& derivatives_;
};

/// The interpolating polynomial of CVODES's last step (its Nordsieck array, of the step's order q)
/// as Taylor coefficients at the step's end t_n, read with q + 1 CVodeGetDky calls: a step that
/// passed more than q + 1 samples (a long record at a loose tolerance passes dozens) then reads
/// each at the cost of a Horner sum instead of a call. The same polynomial CVodeGetDky evaluates,
/// to rounding (measured: 1.5e-15 of a channel's largest value on the diagnosis's records, run
/// either way). Vector 0 is the state, vector i > 0 sensitivity i - 1.
class StepPolynomial {
 public:
  explicit StepPolynomial(int sensitivities) : vectors_(1 + sensitivities) {}

  /// Reads the step that ended at t: the state's coefficients, and the sensitivities' into their
  /// scratch vectors.
  void read(void* cv, double t, int order, N_Vector scratch, N_Vector* sensitivity_scratch) {
    end_ = t;
    order_ = order;
    coefficients_.resize(static_cast<std::size_t>((order + 1) * vectors_ * State::size));
    double factorial = 1.0;
    for (int k = 0; k <= order; ++k) {
      if (k > 0) factorial *= k;
      check_flag(CVodeGetDky(cv, t, k, scratch), "CVodeGetDky", t);
      store(k, 0, scratch, factorial);
      if (vectors_ > 1) {
        check_flag(CVodeGetSensDky(cv, t, k, sensitivity_scratch), "CVodeGetSensDky", t);
        for (int i = 1; i < vectors_; ++i) store(k, i, sensitivity_scratch[i - 1], factorial);
      }
    }
  }

  /// Vector v of the polynomial at `time` (within the step) into `out`.
  void evaluate(double time, int v, N_Vector out) const {
    const double dt = time - end_;
    for (int j = 0; j < State::size; ++j) {
      double value = coefficient(order_, v, j);
      for (int k = order_ - 1; k >= 0; --k) value = value * dt + coefficient(k, v, j);
      NV_Ith_S(out, j) = value;
    }
  }

 private:
  std::size_t index(int k, int v, int j) const {
    return static_cast<std::size_t>((k * vectors_ + v) * State::size + j);
  }
  double coefficient(int k, int v, int j) const { return coefficients_[index(k, v, j)]; }
  void store(int k, int v, N_Vector derivative, double factorial) {
    for (int j = 0; j < State::size; ++j) coefficients_[index(k, v, j)] = NV_Ith_S(derivative, j) / factorial;
  }

  int vectors_;
  int order_ = 0;
  double end_ = 0.0;
  std::vector<double> coefficients_;  // [order][vector][state component]
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

namespace {

/// A sink that copies each block into `result` (sized beforehand).
SampleSink collect_into(SimulationResult& result) {
  return [&result](std::size_t first, const SimulationResult& block) {
    const auto at = static_cast<std::ptrdiff_t>(first);
    const auto from = outputs(block);
    const auto to = outputs(result);
    for (std::size_t c = 0; c < from.size(); ++c) std::copy(from[c]->begin(), from[c]->end(), to[c]->begin() + at);
  };
}

/// A result with the trajectory's columns and room for every output.
SimulationResult sized_result(const ElongationTrajectory& trajectory) {
  SimulationResult result;
  result.time_s = trajectory.time();
  result.elongation_m = trajectory.elongation();
  for (std::vector<double>* column : outputs(result)) column->resize(trajectory.size());
  return result;
}

/// \throws InvalidInput naming the first sample whose length leaves the braid's range for `model`.
void check_lengths(const MuscleModel& model, const ElongationTrajectory& trajectory) {
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
}

/// An array of N_Vectors (the sensitivities), destroyed together.
struct VectorArray {
  N_Vector* vectors = nullptr;
  int count = 0;
  VectorArray(int n, N_Vector like) : vectors(n > 0 ? N_VCloneVectorArray(n, like) : nullptr), count(n) {
    if (n > 0 && !vectors) throw SolverError("N_VCloneVectorArray failed");
  }
  VectorArray(const VectorArray&) = delete;
  VectorArray& operator=(const VectorArray&) = delete;
  ~VectorArray() {
    if (vectors) N_VDestroyVectorArray(vectors, count);
  }
};

/// Absolute tolerances by each state's scale: the temperature's, relative to the ambient
/// temperature, carried over to the gas mass and to stresses of order 1 MPa; the energies'.
State absolute_tolerances(const SimulatorConfig& config, const MuscleModel& model) {
  const double relative = config.absolute_tolerance_K / model.initial_temperature();
  State out;
  out[State::temperature_K] = config.absolute_tolerance_K;
  out[State::gas_mass_kg] = relative * model.gas_mass();
  out[State::viscous_stress_l_Pa] = relative * 1e6;
  out[State::viscous_stress_h_Pa] = relative * 1e6;
  for (int i : {State::work_J, State::heat_lost_J, State::friction_dissipated_J}) out[i] = config.absolute_tolerance_J;
  return out;
}

/// Whether state `j` moves in a run of `model`: the energies always; the gas temperature unless
/// the gas is isothermal (a polytropic index of 1, or a heat exchange that is instant); the gas
/// mass through a leak; the viscous stresses when the bladder's Maxwell branch has a strength. A
/// state that does not move has a rate of exactly zero wherever the run goes (the rates of
/// MuscleModel::evaluate: each is a product with the zero index, leak rate or strength), so
/// holding it where it starts is the run itself.
bool moves(const MuscleModel& model, int j) {
  const MuscleParams& params = model.params();
  switch (j) {
    case State::temperature_K:
      return params.gas.process == GasProcess::heat_transfer ? params.gas.heat_transfer_time_constant_s > 0.0
                                                             : params.gas.polytropic_index != 1.0;
    case State::gas_mass_kg:
      return params.extensions.leak_rate_per_s > 0.0;
    case State::viscous_stress_l_Pa:
    case State::viscous_stress_h_Pa:
      return params.extensions.viscoelastic_strength > 0.0;
    default:
      return true;
  }
}

/// The components of the state a Boost.Odeint method integrates, each in units of its absolute
/// tolerance over the temperature's, so that odeint's one absolute tolerance is the CVODES path's
/// per component (the relative one is scale-free); the others are held where the run starts.
class ScaledState {
 public:
  /// Every component, or (`moving_only`) those that `moves` in a run of `model`, in State's order.
  ScaledState(const SimulatorConfig& config, const MuscleModel& model, bool moving_only) : held_(model.initial()) {
    const State absolute = absolute_tolerances(config, model);
    for (int j = 0; j < State::size; ++j) {
      if (moving_only && !moves(model, j)) continue;
      index_[size_] = j;
      unit_[size_] = absolute[j] / config.absolute_tolerance_K;
      ++size_;
    }
  }

  /// How many components are integrated.
  std::size_t size() const { return size_; }
  /// How many of them lead the energies (the energies are always the last three).
  std::size_t states() const { return size_ - 3; }

  template <class Vector>
  State to_state(const Vector& z) const {
    State y = held_;
    for (std::size_t i = 0; i < size_; ++i) y[index_[i]] = z[i] * unit_[i];
    return y;
  }
  template <class Vector>
  void from_state(const State& y, Vector& z) const {
    for (std::size_t i = 0; i < size_; ++i) z[i] = y[index_[i]] / unit_[i];
  }
  /// The integrated components' rates of `rate`, d(state)/dt.
  template <class Vector>
  void rates(const State& rate, Vector& dz) const {
    for (std::size_t i = 0; i < size_; ++i) dz[i] = rate[index_[i]] / unit_[i];
  }

 private:
  State held_;
  std::array<int, State::size> index_{};
  std::array<double, State::size> unit_{};
  std::size_t size_ = 0;
};

/// The right-hand side the Boost.Odeint methods step: the model's rates at time `t` on the scaled
/// state `z`, counted as one evaluation.
template <class Vector>
void odeint_rates(const MuscleModel& model, const ElongationTrajectory& trajectory, const ScaledState& scaled,
                  RunWorkspace& workspace, const Vector& z, Vector& dzdt, double t, SolverStatistics& statistics) {
  const std::size_t k = workspace.segment(t);
  const MuscleOutputs out =
      model.evaluate_with(workspace.rhs, RunWorkspace::length(model, trajectory, t, k), trajectory.segment_velocity(k),
                          scaled.to_state(z), ShapeParts::kinematics);
  scaled.rates(out.rate, dzdt);
  ++statistics.rhs_evaluations;
}

/// The run loop of the Boost.Odeint methods: `stepper`, a dense-output stepper, steps `system`
/// (its right-hand side, or with a Rosenbrock method the pair of it and its Jacobian) from `z`
/// piece by piece between the corners as the CVODES loop goes, each sample read off the dense
/// output of the step that passed it. A piece's last step is shortened to end on its corner: the
/// right-hand side is never evaluated past it. The step a piece ends with starts the next one.
/// \throws SolverError naming `name` where the state stops being finite, the steps between two
///         samples exceed max_steps, or odeint's step control fails.
template <class Stepper, class System, class Vector>
void integrate_dense(const char* name, const SimulatorConfig& config, const MuscleModel& model,
                     const ElongationTrajectory& trajectory, RunWorkspace& workspace, const ScaledState& scaled,
                     Stepper& stepper, System system, Vector z, BlockRecorder& recorder, SolverStatistics& statistics) {
  namespace odeint = boost::numeric::odeint;
  const auto& time = trajectory.time();
  const double corner = corner_jump(trajectory, config);
  double step = 0.0;
  std::size_t k = 0;
  try {
    while (k + 1 < trajectory.size()) {
      const std::size_t end = piece_end(trajectory, k, corner);
      workspace.piece_start = k;
      workspace.piece_end = end;
      if (k > 0) ++statistics.restarts;
      const double length = time[end] - time[k];
      double t = time[k];
      stepper.initialize(z, t, step > 0.0 ? std::min(step, length) : 1e-3 * (time[k + 1] - time[k]));
      std::size_t sample = k + 1;
      double steps_since_sample = 0;
      while (sample <= end) {
        if (++steps_since_sample > config.max_steps) {
          throw SolverError(detail::message(name, " took more than ", config.max_steps,
                                            " steps before the sample at t = ", time[sample],
                                            " s (SimulatorConfig.max_steps)"));
        }
        // A step that would pass the corner restarts shortened to end on it (one more evaluation).
        if (t + stepper.current_time_step() >= time[end]) {
          z = stepper.current_state();
          stepper.initialize(z, t, time[end] - t);
        }
        t = stepper.do_step(system).second;
        ++statistics.steps;
        // The shortened step ends on the corner to rounding.
        const bool at_corner = time[end] - t <= 1e-14 * std::max(std::abs(time[end]), length);
        for (const double value : stepper.current_state()) {
          if (!std::isfinite(value)) {
            throw SolverError(detail::message(name, ": the state is not finite at t = ", t, " s"));
          }
        }
        for (; sample <= end && (time[sample] <= t || (sample == end && at_corner)); ++sample) {
          stepper.calc_state(time[sample], z);
          recorder.record(sample, model, workspace.output, trajectory.segment_velocity(sample - 1), scaled.to_state(z),
                          statistics);
          steps_since_sample = 0;
        }
      }
      step = stepper.current_time_step();
      k = end;  // z holds the state at the corner
    }
  } catch (const odeint::odeint_error& error) {
    throw SolverError(detail::message(name, " failed at t = ", time[k], " s or later: ", error.what()));
  }
}

/// The run loop of IntegrationMethod::dopri5: Dormand-Prince 5(4), explicit, with its dense
/// output (Boost.Odeint's controlled runge_kutta_dopri5), on every component of the state.
SolverStatistics integrate_explicit(const SimulatorConfig& config, const MuscleModel& model,
                                    const ElongationTrajectory& trajectory, std::size_t block_size,
                                    const SampleSink& sink, const ShapeTable* shapes) {
  namespace odeint = boost::numeric::odeint;
  using Vector = std::array<double, State::size>;
  check_lengths(model, trajectory);
  const ScaledState scaled(config, model, false);

  SolverStatistics statistics;
  statistics.method = IntegrationMethod::dopri5;
  RunWorkspace workspace{model, trajectory, 0, 1, nullptr, {}, {}, nullptr};
  const auto rhs = [&](const Vector& z, Vector& dzdt, double t) {
    odeint_rates(model, trajectory, scaled, workspace, z, dzdt, t, statistics);
  };

  const ShapeTable* tabulated = shapes && shapes->applies_to(model, trajectory) ? shapes : nullptr;
  BlockRecorder recorder(trajectory, block_size, sink, tabulated);
  const State initial = model.initial();
  Vector z;
  scaled.from_state(initial, z);
  recorder.record(0, model, workspace.output, trajectory.segment_velocity(0), initial, statistics);
  auto stepper = odeint::make_dense_output(config.absolute_tolerance_K, config.relative_tolerance, config.max_step_s,
                                           odeint::runge_kutta_dopri5<Vector>());
  integrate_dense("dopri5", config, model, trajectory, workspace, scaled, stepper, rhs, z, recorder, statistics);
  return statistics;
}

/// Hairer and Wanner's RODAS4 coefficients as Boost.Odeint holds them, but for d4, the sum of
/// stage 4's gamma row that weighs the right-hand side's rate in time: Boost 1.74 gives it with
/// the wrong sign (+0.0362), which costs the method its order wherever the right-hand side
/// depends on time, as the motion makes ours: on the pair y' = cos t, z' = -50 (z - sin t) over
/// 20 s it took 31 times the steps at rtol 1e-8 and ended 5e-6 off, where RODAS4's d4 ends at
/// rounding.
struct Rodas4Coefficients : boost::numeric::odeint::default_rosenbrock_coefficients<double> {
  const double d4 = -0.3620000000000023e-01;  // hides the base's d4: odeint reads it by name
};

/// The run loop of IntegrationMethod::rosenbrock4: Boost.Odeint's Rosenbrock 4(3) method with its
/// dense output, on the states that move (`moves`) and the energies, the others held. Each step
/// factorises I / (gamma h) - J once and solves with it six times, each stage one evaluation: no
/// Newton iteration, no history. The Jacobian J is differenced on the states that move alone (a
/// column each, from the step's first evaluation), as is the right-hand side's rate in time (the
/// motion's); nothing depends on the energies, so their columns are zero.
SolverStatistics integrate_rosenbrock(const SimulatorConfig& config, const MuscleModel& model,
                                      const ElongationTrajectory& trajectory, std::size_t block_size,
                                      const SampleSink& sink, const ShapeTable* shapes) {
  namespace odeint = boost::numeric::odeint;
  using Vector = boost::numeric::ublas::vector<double>;
  using Matrix = boost::numeric::ublas::matrix<double>;
  check_lengths(model, trajectory);
  const ScaledState scaled(config, model, true);
  const std::size_t n = scaled.size();

  SolverStatistics statistics;
  statistics.method = IntegrationMethod::rosenbrock4;
  RunWorkspace workspace{model, trajectory, 0, 1, nullptr, {}, {}, nullptr};
  const auto evaluate = [&](const Vector& z, Vector& dzdt, double t) {
    odeint_rates(model, trajectory, scaled, workspace, z, dzdt, t, statistics);
  };
  // odeint asks for the rates at a step's start and then for the Jacobian there: the Jacobian
  // starts from those rates.
  Vector first_z(n), first_rates(n), moved(n), moved_rates(n);
  double first_t = std::numeric_limits<double>::quiet_NaN();
  const auto rhs = [&](const Vector& z, Vector& dzdt, double t) {
    evaluate(z, dzdt, t);
    first_z = z;
    first_rates = dzdt;
    first_t = t;
  };
  const double root_epsilon = std::sqrt(std::numeric_limits<double>::epsilon());
  const auto jacobian = [&](const Vector& z, Matrix& jac, double t, Vector& dfdt) {
    ++statistics.jacobian_evaluations;
    ++statistics.linear_solver_setups;
    if (!(t == first_t && std::equal(z.begin(), z.end(), first_z.begin()))) {
      evaluate(z, first_rates, t);
      first_z = z;
      first_t = t;
    }
    jac.clear();
    for (std::size_t j = 0; j < scaled.states(); ++j) {
      moved = z;
      moved[j] += root_epsilon * std::max(std::abs(z[j]), 1.0);
      const double h = moved[j] - z[j];
      evaluate(moved, moved_rates, t);
      for (std::size_t i = 0; i < n; ++i) jac(i, j) = (moved_rates[i] - first_rates[i]) / h;
    }
    // Into the piece: its motion is one smooth piece (corners restart), so is the quotient.
    const auto& time = trajectory.time();
    const double piece = time[workspace.piece_end] - time[workspace.piece_start];
    const double later = t + root_epsilon * std::max(std::abs(t), piece);
    evaluate(z, moved_rates, later);
    for (std::size_t i = 0; i < n; ++i) dfdt[i] = (moved_rates[i] - first_rates[i]) / (later - t);
  };

  const ShapeTable* tabulated = shapes && shapes->applies_to(model, trajectory) ? shapes : nullptr;
  BlockRecorder recorder(trajectory, block_size, sink, tabulated);
  const State initial = model.initial();
  Vector z(n);
  scaled.from_state(initial, z);
  recorder.record(0, model, workspace.output, trajectory.segment_velocity(0), initial, statistics);
  auto stepper = odeint::make_dense_output(config.absolute_tolerance_K, config.relative_tolerance, config.max_step_s,
                                           odeint::rosenbrock4<double, Rodas4Coefficients>());
  integrate_dense("rosenbrock4", config, model, trajectory, workspace, scaled, stepper, std::make_pair(rhs, jacobian),
                  z, recorder, statistics);
  statistics.error_test_failures = statistics.jacobian_evaluations - statistics.steps;
  return statistics;
}

/// The run loop of Simulator::run_blocks and run_sensitivities: with `moved` (and `derivatives`
/// to fill), the sensitivities to the moved models are integrated beside the state, by BDF. A
/// run by dopri5 or rosenbrock4 (asked for, or auto's pick) goes to integrate_explicit or
/// integrate_rosenbrock.
SolverStatistics integrate(const SimulatorConfig& config, const MuscleModel& model,
                           const ElongationTrajectory& trajectory, std::size_t block_size, const SampleSink& sink,
                           const ShapeTable* shapes, MovedModels* moved, std::vector<SimulationResult>* derivatives) {
  IntegrationMethod method = config.method;
  if (moved) {
    method = IntegrationMethod::bdf;  // the sensitivities' corrector is Newton's
  } else if (method == IntegrationMethod::automatic) {
    if (!estimate_stiffness(model, trajectory, config).stiff()) {
      method = IntegrationMethod::dopri5;
    } else {
      method = config.relative_tolerance >= kRosenbrockTightestTolerance ? IntegrationMethod::rosenbrock4
                                                                         : IntegrationMethod::bdf;
    }
  }
  if (method == IntegrationMethod::dopri5) {
    return integrate_explicit(config, model, trajectory, block_size, sink, shapes);
  }
  if (method == IntegrationMethod::rosenbrock4) {
    return integrate_rosenbrock(config, model, trajectory, block_size, sink, shapes);
  }
  const auto& time = trajectory.time();
  check_lengths(model, trajectory);

  auto context = cvodes::make_context();
  SUNContext ctx = *context;
  cvodes::Vector y(N_VNew_Serial(State::size, ctx));
  cvodes::Vector tolerances(N_VNew_Serial(State::size, ctx));
  cvodes::Vector sample_state(N_VNew_Serial(State::size, ctx));  // CVODES's interpolant at a sample
  if (!y || !tolerances || !sample_state) throw SolverError("N_VNew_Serial failed");
  const State initial = model.initial();
  std::copy(initial.values.begin(), initial.values.end(), NV_DATA_S(y.get()));
  const State absolute = absolute_tolerances(config, model);
  std::copy(absolute.values.begin(), absolute.values.end(), NV_DATA_S(tolerances.get()));

  RunWorkspace workspace{model, trajectory, 0, 1, nullptr, {}, {}, moved};
  const double t0 = time.front();
  const cvodes::Solver solver =
      cvodes::make_solver(method, ctx, muscle_rhs, t0, y.get(), &workspace, config.relative_tolerance, tolerances.get(),
                          config.max_steps, config.max_step_s);
  void* cv = solver.get();

  // The sensitivities: s_i(0) = (y0_i - y0) / h_i, from each moved model's own initial state;
  // absolute tolerances the state's (parameters of order one), for the corrector's convergence test.
  const int count = moved ? static_cast<int>(moved->models.size()) : 0;
  VectorArray sensitivities(count, y.get());
  VectorArray sample_sensitivities(count, y.get());
  VectorArray sensitivity_tolerances(count, y.get());
  for (int i = 0; i < count; ++i) {
    const auto m = static_cast<std::size_t>(i);
    const State moved_initial = moved->models[m].initial();
    for (int j = 0; j < State::size; ++j) {
      NV_Ith_S(sensitivities.vectors[i], j) = (moved_initial[j] - initial[j]) / moved->steps[m];
    }
    N_VScale(1.0, tolerances.get(), sensitivity_tolerances.vectors[i]);
  }
  if (count > 0) {
    check_flag(CVodeSensInit(cv, count, CV_STAGGERED, sensitivity_rhs, sensitivities.vectors), "CVodeSensInit", t0);
    check_flag(CVodeSensSVtolerances(cv, config.relative_tolerance, sensitivity_tolerances.vectors),
               "CVodeSensSVtolerances", t0);
    // Outside the error test: the steps stay the state's, and the sensitivities' accuracy (3e-5 of
    // a slope at rtol 1e-8, tests/cpp/sensitivities.test.cpp) is far finer than a fit needs.
    check_flag(CVodeSetSensErrCon(cv, SUNFALSE), "CVodeSetSensErrCon", t0);
  }

  SolverStatistics statistics;
  // A table for another build, other lengths or compliant fibers is left alone: the shapes are
  // then solved as without one.
  const ShapeTable* tabulated = shapes && shapes->applies_to(model, trajectory) ? shapes : nullptr;
  BlockRecorder recorder(trajectory, block_size, sink, tabulated);
  std::optional<DerivativeRecorder> differentiator;
  if (moved) differentiator.emplace(*moved, trajectory, model.initial_state().length_m, *derivatives);
  // Sample k's friction reads the elongation rate of the segment that ends there (the first at the start).
  const auto record = [&](std::size_t sample, std::size_t segment, const State& state, N_Vector* state_sensitivities) {
    const MuscleOutputs out =
        recorder.record(sample, model, workspace.output, trajectory.segment_velocity(segment), state, statistics);
    if (differentiator) differentiator->record(sample, segment, state, state_sensitivities, out, statistics);
  };
  record(0, 0, initial, sensitivities.vectors);
  StepPolynomial polynomial(count);

  // Integrate piece by piece between corners, where the elongation rate jumps: CVODES stops
  // exactly there (its stop time) and restarts its BDF history. Inside a piece it takes one
  // step per call, and every sample the step passed is read off its interpolating polynomial
  // (CVodeGetDky, which CV_NORMAL mode uses too, or StepPolynomial where the step passed many):
  // one call per step, not per sample, and the samples do not steer the steps.
  const double corner = corner_jump(trajectory, config);
  double t = t0;
  std::size_t k = 0;
  while (k + 1 < trajectory.size()) {
    const std::size_t end = piece_end(trajectory, k, corner);
    workspace.piece_start = k;
    workspace.piece_end = end;
    if (k > 0) {
      add_statistics(solver, statistics);
      check_flag(CVodeReInit(cv, t, y.get()), "CVodeReInit", t);
      if (count > 0) {
        double at = t;
        check_flag(CVodeGetSens(cv, &at, sensitivities.vectors), "CVodeGetSens", t);
        check_flag(CVodeSensReInit(cv, CV_STAGGERED, sensitivities.vectors), "CVodeSensReInit", t);
      }
      ++statistics.restarts;
    }
    check_flag(CVodeSetStopTime(cv, time[end]), "CVodeSetStopTime", t);
    std::size_t sample = k + 1;
    double steps_since_sample = 0;
    while (sample <= end) {
      while (t < time[sample]) {
        // CVODES counts its mxstep per call; one step per call, the simulator counts them.
        if (++steps_since_sample > config.max_steps) {
          throw SolverError(detail::message("CVode failed with CV_TOO_MUCH_WORK at t = ", t, " s: more than ",
                                            config.max_steps, " steps before the sample at t = ", time[sample],
                                            " s (SimulatorConfig.max_steps)"));
        }
        // The output time only sizes the first step after a (re)start: the piece's end, so the
        // samples leave the step sequence alone.
        const int flag = CVode(cv, time[end], y.get(), &t, CV_ONE_STEP);
        if (workspace.error) std::rethrow_exception(workspace.error);
        check_flag(flag, "CVode", t);
      }
      std::size_t passed = sample;  // one past the last sample this step passed
      while (passed <= end && time[passed] <= t) ++passed;
      int order = 0;
      check_flag(CVodeGetLastOrder(cv, &order), "CVodeGetLastOrder", t);
      const bool horner = passed - sample > static_cast<std::size_t>(order) + 1;
      if (horner) polynomial.read(cv, t, order, sample_state.get(), sample_sensitivities.vectors);
      for (; sample < passed; ++sample) {
        const bool sensitivities_read = count > 0 && differentiator->wants(sample);
        if (horner) {
          polynomial.evaluate(time[sample], 0, sample_state.get());
          for (int i = 0; sensitivities_read && i < count; ++i) {
            polynomial.evaluate(time[sample], i + 1, sample_sensitivities.vectors[i]);
          }
        } else {
          check_flag(CVodeGetDky(cv, time[sample], 0, sample_state.get()), "CVodeGetDky", time[sample]);
          if (sensitivities_read) {
            check_flag(CVodeGetSensDky(cv, time[sample], 0, sample_sensitivities.vectors), "CVodeGetSensDky",
                       time[sample]);
          }
        }
        record(sample, sample - 1, to_state(sample_state.get()), sample_sensitivities.vectors);
        steps_since_sample = 0;
      }
    }
    k = end;
  }
  add_statistics(solver, statistics);
  if (moved) statistics.sensitivity_rhs_evaluations = moved->rhs_evaluations;
  return statistics;
}

/// Per sample of a trajectory of `size`, whether `rows` holds it (empty: none is marked, and
/// MovedModels reads that as every one).
std::vector<char> wanted_samples(const std::vector<std::size_t>& rows, std::size_t size) {
  std::vector<char> wanted(rows.empty() ? 0 : size, 0);
  for (std::size_t j = 0; j < rows.size(); ++j) {
    if (rows[j] >= size) {
      throw InvalidInput(detail::message("Simulator.run_sensitivities: rows[", j, "] = ", rows[j],
                                         " is past the trajectory's last sample, ", size - 1));
    }
    if (j > 0 && rows[j] <= rows[j - 1]) {
      throw InvalidInput(detail::message("Simulator.run_sensitivities: rows[", j, "] = ", rows[j],
                                         " does not increase (rows[", j - 1, "] = ", rows[j - 1], ")"));
    }
    wanted[rows[j]] = 1;
  }
  return wanted;
}

}  // namespace

SimulationResult Simulator::run(const MuscleModel& model, const ElongationTrajectory& trajectory,
                                const ShapeTable* shapes) const {
  SimulationResult result = sized_result(trajectory);
  result.statistics = run_blocks(model, trajectory, kCollectBlockSize, collect_into(result), shapes);
  return result;
}

SolverStatistics Simulator::run_blocks(const MuscleModel& model, const ElongationTrajectory& trajectory,
                                       std::size_t block_size, const SampleSink& sink, const ShapeTable* shapes) const {
  if (block_size == 0) throw InvalidInput("Simulator.run_blocks: block_size must be at least 1");
  return integrate(config_, model, trajectory, block_size, sink, shapes, nullptr, nullptr);
}

SensitivityResult Simulator::run_sensitivities(const MuscleModel& model, const std::vector<MuscleModel>& moved,
                                               const std::vector<double>& steps, const ElongationTrajectory& trajectory,
                                               const ShapeTable* shapes,
                                               const std::vector<ElongationTrajectory>& moved_motions,
                                               const std::vector<std::size_t>& rows) const {
  if (moved.size() != steps.size()) {
    throw InvalidInput(
        detail::message("Simulator.run_sensitivities: ", moved.size(), " moved models for ", steps.size(), " steps"));
  }
  if (!moved_motions.empty() && moved_motions.size() != moved.size()) {
    throw InvalidInput(detail::message("Simulator.run_sensitivities: ", moved_motions.size(), " moved motions for ",
                                       moved.size(), " moved models (give none, or one each)"));
  }
  MovedModels moved_models{moved,
                           steps,
                           {},
                           std::vector<MuscleWorkspace>(moved.size()),
                           std::vector<MuscleWorkspace>(moved.size()),
                           {},
                           wanted_samples(rows, trajectory.size()),
                           0};
  for (std::size_t i = 0; i < moved.size(); ++i) {
    if (!(std::isfinite(steps[i]) && steps[i] != 0.0)) {
      throw InvalidInput(detail::message("Simulator.run_sensitivities: step ", i, " is ", steps[i],
                                         "; it must be finite and not zero"));
    }
    const ElongationTrajectory& motion = moved_motions.empty() ? trajectory : moved_motions[i];
    if (motion.time() != trajectory.time()) {
      throw InvalidInput(detail::message("Simulator.run_sensitivities: moved motion ", i,
                                         " is not sampled at the trajectory's times"));
    }
    check_lengths(moved[i], motion);
    moved_models.motions.push_back(&motion);
    moved_models.shapes.push_back(shapes && shapes->applies_to(moved[i], motion) ? shapes : nullptr);
  }
  SensitivityResult out;
  out.run = sized_result(trajectory);
  out.run.statistics = integrate(config_, model, trajectory, kCollectBlockSize, collect_into(out.run), shapes,
                                 &moved_models, &out.derivatives);
  return out;
}

}  // namespace pamkit
