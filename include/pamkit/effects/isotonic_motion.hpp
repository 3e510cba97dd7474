#pragma once
/// \file
/// An isotonic test over time: a mass hanging on the muscle while the supplied pressure moves,
/// integrated with CVODES (the quasi-static path is `isotonic_lengths` in pipeline.hpp).

#include <optional>
#include <vector>

#include "pamkit/effects/pipeline.hpp"
#include "pamkit/fields.hpp"
#include "pamkit/sim/simulator.hpp"

namespace pamkit {

/// Integrator settings of `isotonic_motion`.
struct IsotonicMotionConfig {
  static constexpr const char* kName = "IsotonicMotionConfig";

  double relative_tolerance = 1e-8;          ///< CVODE relative tolerance [1]
  double absolute_tolerance_m = 1e-10;       ///< CVODE absolute tolerance on the length [m]
  double absolute_tolerance_m_per_s = 1e-8;  ///< CVODE absolute tolerance on the velocity [m/s]
  double max_steps = 50000;                  ///< most internal steps between two samples [1]
  double max_step_s = 0.0;                   ///< largest internal step [s]; 0: no limit

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("relative_tolerance", &IsotonicMotionConfig::relative_tolerance,
          FieldInfo{"1", 1e-14, 1e-2, "relative tolerance"});
    visit("absolute_tolerance_m", &IsotonicMotionConfig::absolute_tolerance_m,
          FieldInfo{"m", 1e-16, 1e-2, "absolute tolerance on the length"});
    visit("absolute_tolerance_m_per_s", &IsotonicMotionConfig::absolute_tolerance_m_per_s,
          FieldInfo{"m/s", 1e-16, 1.0, "absolute tolerance on the velocity"});
    visit("max_steps", &IsotonicMotionConfig::max_steps, FieldInfo{"1", 10, 1e9, "most steps between samples"});
    visit("max_step_s", &IsotonicMotionConfig::max_step_s, FieldInfo{"s", 0.0, 1e9, "largest step (0: no limit)"});
  }
  void validate() const { validate_fields(*this); }
};

/// The motion of an isotonic test; every vector has one entry per pressure sample.
struct IsotonicMotion {
  std::vector<double> time_s;             ///< sample times [s]
  std::vector<double> length_m;           ///< muscle length [m]
  std::vector<double> velocity_m_per_s;   ///< lengthening rate [m/s] (> 0 while the load wins)
  std::vector<double> force_N;            ///< the muscle's tension, friction included [N]
  std::vector<double> gauge_pressure_Pa;  ///< the gauge pressure that drove the model (effects applied) [Pa]
  SolverStatistics statistics;            ///< CVODES counters, summed over the restarts
};

/// Integrates a mass `mass_kg` hanging on the muscle under a constant load `load_N` (its weight,
/// or weight plus any constant pull) while the supplied gauge pressure moves through
/// `gauge_pressures_Pa` at `time_s`, linearly between samples:
///     dL/dt = v,   m dv/dt = load_N - F(L, p(t), v, branch),
/// the length growing while the load wins. F is the tension of `detail::supplied_force`: gas,
/// bladder and the tanh friction at velocity v, less the pressurise/vent hysteresis on the
/// branch `pressure_branches` gives (the branch of the sample ending each segment; CVODES
/// restarts where it flips), plus what the Maxwell-slip elements hold (muscle/slip.hpp: states
/// of the motion, each following the length with its stiffness until it slips), through a braid
/// that cannot push when the slack band is on. A light load on a slack muscle falls freely until
/// the bladder or the gas carries it.
/// Effects act as in `isotonic_lengths`: physical ones through the parameters, the supplied
/// pressure's transducer through the pressure.
/// \param time_s              sample times [s], strictly increasing, at least two
/// \param gauge_pressures_Pa  supplied gauge pressure at each sample [Pa]
/// \param load_N              constant load on the muscle [N]
/// \param mass_kg             moving mass [kg], > 0
/// \param start_length_m      length at time_s[0], at rest, the slip elements empty [m]; by
///                            default the quasi-static equilibrium `isotonic_lengths` finds for
///                            the first sample (searched from the deflated length, the slip
///                            elements as that path leaves them; the end of its search range if
///                            it finds none there)
/// \throws InvalidInput for mismatched sizes, times not increasing, a start outside the braid's
///         range, or a length that reaches the braid's range (naming the time and the samples
///         around it); InvalidParameter for a mass not > 0, a series compliance (the build's
///         series_compliance_m_per_N not 0), a bad config or an effect that cannot act here;
///         SolverError with the CVODES flag's name if integration fails.
IsotonicMotion isotonic_motion(const MuscleParams& params, const std::vector<double>& time_s,
                               const std::vector<double>& gauge_pressures_Pa, double load_N, double mass_kg,
                               std::optional<double> start_length_m = std::nullopt,
                               const std::vector<EffectPtr>& effects = {}, const IsotonicMotionConfig& config = {});

}  // namespace pamkit
