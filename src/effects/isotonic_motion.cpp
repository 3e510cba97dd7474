// CVODES glue for pamkit::isotonic_motion: a mass on the muscle, integrated sample by sample and
// restarted where the pressurise/vent branch flips, with the handles and flag checks of
// cvodes_support.hpp.

#include "pamkit/effects/isotonic_motion.hpp"

#include <nvector/nvector_serial.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>

#include "../sim/cvodes_support.hpp"

namespace pamkit {
namespace {

using cvodes::check_flag;

// The length, its rate, and, with Maxwell-slip friction (muscle/slip.hpp), what each element
// holds. Without it the state is the length and its rate alone: states that never move would
// dilute the error test's root mean square.
enum MotionState : int { length_index = 0, velocity_index = 1, slip_index = 2 };

/// The size of the motion's state for these parameters.
int motion_state_size(const MuscleParams& extended) {
  return extended.extensions.slip_force_N > 0.0 ? slip_index + static_cast<int>(kSlipElements) : slip_index;
}

/// The slip elements' forces in the motion's state (all zero without them).
SlipState slip_of(N_Vector y) {
  SlipState slip;
  if (N_VGetLength(y) <= slip_index) return slip;
  for (std::size_t i = 0; i < kSlipElements; ++i) slip.force_N[i] = NV_Ith_S(y, slip_index + static_cast<int>(i));
  return slip;
}

/// Per-run mutable workspace handed to CVODES as user data.
struct MotionWorkspace {
  const BraidGeometry& geometry;
  const MuscleParams& extended;
  const std::vector<double>& time;
  const std::vector<double>& driving_Pa;
  double load_N;
  double mass_kg;
  double branch;            // pressurise (+1) or vent (-1) along the piece being integrated
  std::size_t piece_start;  // first sample of that piece
  std::size_t piece_end;    // its last sample
  double shortest;          // the range the motion may reach before it stops [m]
  double longest;
  std::exception_ptr error;  // an exception thrown inside a callback, rethrown after CVode returns
  // Each Maxwell-slip element sticks (its force follows the length) or slips (it holds its
  // limit), fixed between restarts: the switch is a root of motion_limits, where CVODES stops.
  std::array<bool, kSlipElements> slipping{};

  /// The segment [t_k, t_k+1] of the piece that holds time t (CVODES may step past samples).
  std::size_t segment(double t) const {
    const auto first = time.begin() + static_cast<std::ptrdiff_t>(piece_start);
    const auto last = time.begin() + static_cast<std::ptrdiff_t>(piece_end);
    const std::size_t k = static_cast<std::size_t>(std::upper_bound(first, last, t) - time.begin());
    return std::clamp(k == 0 ? 0 : k - 1, piece_start, piece_end - 1);
  }
  /// The supplied gauge pressure at time t, linear between samples [Pa].
  double gauge_Pa(double t) const {
    const std::size_t k = segment(t);
    const double share = (t - time[k]) / (time[k + 1] - time[k]);
    return driving_Pa[k] + share * (driving_Pa[k + 1] - driving_Pa[k]);
  }
};

int motion_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
  auto& w = *static_cast<MotionWorkspace*>(user_data);
  const double length = NV_Ith_S(y, length_index);
  const double velocity = NV_Ith_S(y, velocity_index);
  // A trial step beyond the braid's geometry: recoverable, CVODES retries a shorter step. The
  // solution itself stops at the roots of motion_limits, inside that range.
  if (!(length > w.geometry.min_length() && length < w.geometry.max_length())) return 1;
  try {
    const SlipState slip = slip_of(y);
    const double tension = detail::supplied_force(w.geometry, w.extended, w.geometry.shape(length), w.gauge_Pa(t),
                                                  velocity, w.branch, slip.total_N());
    NV_Ith_S(ydot, length_index) = velocity;
    NV_Ith_S(ydot, velocity_index) = (w.load_N - tension) / w.mass_kg;
    // Each element follows the motion with its stiffness until it holds its slip force, and holds
    // it while the motion goes on the same way.
    const ModelExtensions& x = w.extended.extensions;
    const double stiffness = x.slip_force_N > 0.0 ? slip_element_stiffness(x.slip_force_N, x.slip_distance_m) : 0.0;
    for (std::size_t i = 0; x.slip_force_N > 0.0 && i < kSlipElements; ++i) {
      NV_Ith_S(ydot, slip_index + static_cast<int>(i)) = w.slipping[i] ? 0.0 : stiffness * velocity;
    }
    return 0;
  } catch (...) {
    w.error = std::current_exception();
    return -1;  // unrecoverable: CVode returns CV_RHSFUNC_FAIL and isotonic_motion rethrows
  }
}

/// Zero where the length reaches the shortest or the longest length the motion may take; with
/// slip elements, also where a sticking element reaches its slip force, and where a slipping one's
/// motion turns (it sticks again). Each falls through zero (CVodeSetRootDirection -1).
int motion_limits(sunrealtype, N_Vector y, sunrealtype* g, void* user_data) {
  const auto& w = *static_cast<const MotionWorkspace*>(user_data);
  g[0] = NV_Ith_S(y, length_index) - w.shortest;
  g[1] = w.longest - NV_Ith_S(y, length_index);
  if (N_VGetLength(y) > slip_index) {
    const double velocity = NV_Ith_S(y, velocity_index);
    for (std::size_t i = 0; i < kSlipElements; ++i) {
      const double force = NV_Ith_S(y, slip_index + static_cast<int>(i));
      const double limit = slip_element_force(w.extended.extensions.slip_force_N, i);
      g[2 + i] = w.slipping[i] ? (force > 0.0 ? velocity : -velocity) : limit - std::abs(force);
    }
  }
  return 0;
}

/// After a root of an element: the one that reached its slip force now slips (held exactly at
/// it), the one whose motion turned sticks. \returns whether a root was an element's.
bool switch_slip_elements(void* cv, MotionWorkspace& w, N_Vector y) {
  std::array<int, 2 + kSlipElements> found{};
  check_flag(CVodeGetRootInfo(cv, found.data()), "CVodeGetRootInfo", 0.0);
  bool switched = false;
  for (std::size_t i = 0; N_VGetLength(y) > slip_index && i < kSlipElements; ++i) {
    if (found[2 + i] == 0) continue;
    switched = true;
    double& force = NV_Ith_S(y, slip_index + static_cast<int>(i));
    const double limit = slip_element_force(w.extended.extensions.slip_force_N, i);
    w.slipping[i] = !w.slipping[i];
    if (w.slipping[i]) force = force > 0.0 ? limit : -limit;
  }
  return switched;
}

void check_inputs(const std::vector<double>& time_s, const std::vector<double>& gauge_pressures_Pa, double load_N,
                  double mass_kg) {
  if (!(mass_kg > 0.0 && std::isfinite(mass_kg))) {
    throw InvalidParameter(detail::message("isotonic_motion: mass_kg = ", mass_kg,
                                           " kg must be finite and > 0 (a massless load follows isotonic_lengths)"));
  }
  if (!std::isfinite(load_N)) throw InvalidInput(detail::message("isotonic_motion: load_N = ", load_N, " N"));
  if (gauge_pressures_Pa.size() != time_s.size()) {
    throw InvalidInput(
        detail::message("isotonic_motion: ", gauge_pressures_Pa.size(), " pressures for ", time_s.size(), " times"));
  }
  if (time_s.size() < 2) {
    throw InvalidInput(detail::message("isotonic_motion: ", time_s.size(), " samples; a motion needs two or more"));
  }
  for (std::size_t k = 0; k < time_s.size(); ++k) {
    if (!std::isfinite(time_s[k]) || (k > 0 && !(time_s[k] > time_s[k - 1]))) {
      throw InvalidInput(detail::message("isotonic_motion: sample ", k + 1, " has time ", time_s[k],
                                         " s; times must be finite and strictly increasing"));
    }
    if (!std::isfinite(gauge_pressures_Pa[k])) {
      throw InvalidInput(
          detail::message("isotonic_motion: sample ", k + 1, " has pressure ", gauge_pressures_Pa[k], " Pa"));
    }
  }
}

void record(IsotonicMotion& r, const MotionWorkspace& w, std::size_t sample, double length, double velocity,
            double branch, double slip_N) {
  const double gauge = w.driving_Pa[sample];
  r.time_s.push_back(w.time[sample]);
  r.length_m.push_back(length);
  r.velocity_m_per_s.push_back(velocity);
  r.force_N.push_back(
      detail::supplied_force(w.geometry, w.extended, w.geometry.shape(length), gauge, velocity, branch, slip_N));
  r.gauge_pressure_Pa.push_back(gauge);
  ++r.statistics.output_evaluations;
}

}  // namespace

IsotonicMotion isotonic_motion(const MuscleParams& params, const std::vector<double>& time_s,
                               const std::vector<double>& gauge_pressures_Pa, double load_N, double mass_kg,
                               std::optional<double> start_length_m, const std::vector<EffectPtr>& effects,
                               const IsotonicMotionConfig& config) {
  config.validate();
  check_inputs(time_s, gauge_pressures_Pa, load_N, mass_kg);
  if (params.build.series_compliance_m_per_N > 0.0) {
    // The load would hang on a spring: the braid's length an algebraic unknown of every state.
    throw InvalidParameter(detail::message(
        "isotonic_motion: MuscleBuild.series_compliance_m_per_N = ", params.build.series_compliance_m_per_N,
        " m/N: a load's motion is integrated with a rigid series (give 0; settled rows follow isotonic_lengths)"));
  }
  MuscleParams extended = params;
  std::vector<double> driving = gauge_pressures_Pa;
  detail::apply_static_effects(effects, extended, driving);
  const BraidGeometry geometry(extended.build);
  const std::vector<double> branch = pressure_branches(driving);
  // The motion stops a millionth of the braid's range inside it, where the geometry still holds.
  const double margin = 1e-6 * (geometry.max_length() - geometry.min_length());
  MotionWorkspace workspace{geometry,
                            extended,
                            time_s,
                            driving,
                            load_N,
                            mass_kg,
                            branch[1],
                            0,
                            1,
                            geometry.min_length() + margin,
                            geometry.max_length() - margin,
                            nullptr};
  // At rest at the start: given, with nothing in the slip elements; or where the quasi-static
  // path from the deflated length settles, with what the elements took up on it.
  SlipState slip;
  double start = 0.0;
  if (start_length_m) {
    start = *start_length_m;
  } else {
    const IsotonicLengths settled =
        isotonic_lengths(params, {gauge_pressures_Pa.front()}, load_N, params.build.length_m, effects);
    start = settled.length_m.front();
    slip = settled.slip;
  }
  if (!(start > workspace.shortest && start < workspace.longest)) {
    throw InvalidInput(detail::message("isotonic_motion: start_length_m = ", start, " m is outside the braid's range (",
                                       geometry.min_length(), ", ", geometry.max_length(), ") m for this build"));
  }

  auto context = cvodes::make_context();
  SUNContext ctx = *context;
  const int size = motion_state_size(extended);
  cvodes::Vector y(N_VNew_Serial(size, ctx));
  cvodes::Vector tolerances(N_VNew_Serial(size, ctx));
  if (!y || !tolerances) throw SolverError("N_VNew_Serial failed");
  NV_Ith_S(y.get(), length_index) = start;
  NV_Ith_S(y.get(), velocity_index) = 0.0;
  NV_Ith_S(tolerances.get(), length_index) = config.absolute_tolerance_m;
  NV_Ith_S(tolerances.get(), velocity_index) = config.absolute_tolerance_m_per_s;
  // An element's force to the length's tolerance times its stiffness: the force that much motion
  // moves it by.
  const ModelExtensions& extensions = extended.extensions;
  for (std::size_t i = 0; size > slip_index && i < kSlipElements; ++i) {
    const int j = slip_index + static_cast<int>(i);
    NV_Ith_S(y.get(), j) = slip.force_N[i];
    workspace.slipping[i] = false;  // at rest every element sticks
    NV_Ith_S(tolerances.get(), j) =
        config.absolute_tolerance_m * slip_element_stiffness(extensions.slip_force_N, extensions.slip_distance_m);
  }

  // BDF with Newton: the tanh friction of a sharp Kf is stiff; without friction the tight
  // default tolerances keep BDF's numerical damping below them (the energy test measures it).
  double t = time_s.front();
  const cvodes::BdfSolver solver = cvodes::make_bdf(ctx, motion_rhs, t, y.get(), &workspace, config.relative_tolerance,
                                                    tolerances.get(), config.max_steps, config.max_step_s);
  void* cv = solver.get();
  const int roots = size > slip_index ? 2 + static_cast<int>(kSlipElements) : 2;
  check_flag(CVodeRootInit(cv, roots, motion_limits), "CVodeRootInit", t);
  std::array<int, 2 + kSlipElements> falling;  // a length leaving the range, an element switching
  falling.fill(-1);
  check_flag(CVodeSetRootDirection(cv, falling.data()), "CVodeSetRootDirection", t);

  IsotonicMotion result;
  result.time_s.reserve(time_s.size());
  record(result, workspace, 0, start, 0.0, branch[0], slip.total_N());

  // Segment k (from sample k to k+1) is on the branch of sample k+1. Where that flips, the
  // hysteresis force jumps: CVODES restarts its BDF history at the sample. It stops at every
  // sample too, where the pressure's rate jumps, rather than interpolating across the kink
  // (on a slow ramp's turn that costs a quarter more steps and gains two digits).
  std::size_t k = 0;
  while (k + 1 < time_s.size()) {
    std::size_t end = k + 1;
    while (end + 1 < time_s.size() && branch[end + 1] == branch[k + 1]) ++end;
    workspace.branch = branch[k + 1];
    workspace.piece_start = k;
    workspace.piece_end = end;
    if (k > 0) {
      cvodes::add_statistics(solver, result.statistics);
      check_flag(CVodeReInit(cv, t, y.get()), "CVodeReInit", t);
      ++result.statistics.restarts;
    }
    for (std::size_t sample = k + 1; sample <= end; ++sample) {
      check_flag(CVodeSetStopTime(cv, time_s[sample]), "CVodeSetStopTime", t);
      int flag = CVode(cv, time_s[sample], y.get(), &t, CV_NORMAL);
      if (workspace.error) std::rethrow_exception(workspace.error);
      check_flag(flag, "CVode", t);
      // An element switched: its rate jumps, so CVODES restarts there, and goes on to the sample.
      while (flag == CV_ROOT_RETURN && switch_slip_elements(cv, workspace, y.get())) {
        cvodes::add_statistics(solver, result.statistics);
        check_flag(CVodeReInit(cv, t, y.get()), "CVodeReInit", t);
        ++result.statistics.restarts;
        flag = CVode(cv, time_s[sample], y.get(), &t, CV_NORMAL);
        if (workspace.error) std::rethrow_exception(workspace.error);
        check_flag(flag, "CVode", t);
      }
      if (flag == CV_ROOT_RETURN) {
        const double length = NV_Ith_S(y.get(), length_index);
        const bool too_long = length > 0.5 * (workspace.shortest + workspace.longest);
        throw InvalidInput(detail::message(
            "isotonic_motion: at t = ", t, " s (between samples ", sample, " and ", sample + 1, ", gauge ",
            workspace.gauge_Pa(t), " Pa) the length reached ", length, " m, the ", too_long ? "longest" : "shortest",
            " the braid allows (", geometry.min_length(), ", ", geometry.max_length(), ") m: the load of ", load_N,
            " N ",
            too_long ? "outruns what the muscle can carry there" : "is too light to hold the muscle back there"));
      }
      record(result, workspace, sample, NV_Ith_S(y.get(), length_index), NV_Ith_S(y.get(), velocity_index),
             branch[sample], slip_of(y.get()).total_N());
    }
    k = end;
  }
  cvodes::add_statistics(solver, result.statistics);
  return result;
}

}  // namespace pamkit
