#pragma once
/// \file
/// The muscle's force for a controller's loop: one object built once from the parameters, one
/// call per sample that neither throws nor allocates and reports lengths the braid model cannot
/// take by status. Header-only; CMake target pamkit::muscle (Boost headers, no SUNDIALS, no
/// libserialport), and it compiles with -fno-exceptions (docs/realtime.md).
///
/// The force is the library's, not a copy of it: BraidGeometry::shape_unchecked (the shape that
/// BraidGeometry::shape returns after its range check) and detail::supplied_force (muscle_forces'
/// total through the braid's slack, what static_forces reports), so inside the range it equals
/// `braid_tension(muscle_forces(geometry, geometry.shape(L), ...).total, detail::slack_band_N(params))`
/// bit for bit (with a series compliance, at the braid's length instead of L).

#include <cmath>

#include "pamkit/sim/held_braid.hpp"

namespace pamkit {

/// Whether RealtimeMuscle::force could compute the force.
enum class ForceStatus : unsigned char {
  ok,         ///< the force of the model
  too_short,  ///< length <= min_length_m(): the end cones lie flat, the braid model ends there
  too_long,   ///< length >= max_length_m(): the braid has closed onto the end caps
  not_finite  ///< the length is NaN, or the pressure or the velocity is not finite
};

/// The force at one sample.
struct RealtimeForce {
  double force_N;      ///< axial force [N], > 0 in tension; 0 whenever status is not ok
  ForceStatus status;  ///< ok, or why there is no force
};

/// What a controller carries from one RealtimeMuscle::force call to the next when the muscle has
/// friction with memory (`extensions.slip_force_N` > 0): where the braid is and what its
/// Maxwell-slip elements hold (sim/held_braid.hpp). One per muscle in the loop, never shared.
struct RealtimeWorkspace {
  HeldBraidState braid;  ///< at rest until the first call
};

/// A muscle whose force a controller evaluates in its loop. Immutable and cheap to copy; `force`
/// may be called from many threads at once (each with its own workspace).
class RealtimeMuscle {
 public:
  /// Validates `params` and precomputes the braid (fiber length, length range). Build it once,
  /// before the loop.
  /// \throws InvalidParameter naming the bad field (without exceptions: the message on stderr,
  ///         then abort; see PAMKIT_THROW in error.hpp).
  explicit RealtimeMuscle(const MuscleParams& params)
      : params_((params.validate(), params)), geometry_(params_.build) {}

  /// Axial force [N] of the muscle at length `length_m` [m], supplied gauge pressure
  /// `gauge_pressure_Pa` [Pa] and elongation rate `velocity_m_per_s` [m/s] (> 0 stretching,
  /// for friction): gas, bladder and friction, through a braid that cannot push when
  /// `extensions.slack_band_N` > 0 or the fibres are embedded in the membrane. The
  /// pressurise/vent hysteresis (`extensions.pressure_hysteresis`) needs the pressure's history
  /// and is left out: the force lies between its two branches. So are the Maxwell-slip elements,
  /// which need the motion's: the overload with a RealtimeWorkspace carries it. A series
  /// compliance (`build.series_compliance_m_per_N`) puts the braid short of `length_m` by what its
  /// pull stretches it (yielded_braid_length). Outside (min_length_m(), max_length_m()), or for
  /// input that is not finite, the force is 0 N and the status says why. No exception, no
  /// allocation.
  RealtimeForce force(double length_m, double gauge_pressure_Pa, double velocity_m_per_s) const noexcept {
    if (std::isnan(length_m) || !std::isfinite(gauge_pressure_Pa) || !std::isfinite(velocity_m_per_s)) {
      return {0.0, ForceStatus::not_finite};
    }
    if (!(length_m > geometry_.min_length())) return {0.0, ForceStatus::too_short};
    if (!(length_m < geometry_.max_length())) return {0.0, ForceStatus::too_long};
    double braid = length_m;
    if (params_.build.series_compliance_m_per_N > 0.0) {
      const auto carried = [&](double b) {
        return detail::unslackened_supplied_force(geometry_, params_, geometry_.shape_unchecked(b), gauge_pressure_Pa,
                                                  velocity_m_per_s, 0.0, 0.0);
      };
      braid = pulled_braid_length(geometry_, params_, carried, length_m, carried(length_m));
    }
    const MuscleShape shape = geometry_.shape_unchecked(braid);
    return {detail::supplied_force(geometry_, params_, shape, gauge_pressure_Pa, velocity_m_per_s, 0.0),
            ForceStatus::ok};
  }

  /// A workspace at rest: the braid at the deflated length, the slip elements empty.
  RealtimeWorkspace rest() const noexcept { return {braid_at_rest(params_.build)}; }

  /// `force`, with the friction that remembers the motion: the braid settled from `workspace`
  /// (settle_held_braid at branch 0), which it updates. Without slip elements it equals `force`
  /// bit for bit, a series compliance included. Out of range or not finite, the status says so
  /// and the workspace is left as it was. No exception, no allocation.
  RealtimeForce force(RealtimeWorkspace& workspace, double length_m, double gauge_pressure_Pa,
                      double velocity_m_per_s) const noexcept {
    if (std::isnan(length_m) || !std::isfinite(gauge_pressure_Pa) || !std::isfinite(velocity_m_per_s)) {
      return {0.0, ForceStatus::not_finite};
    }
    if (!(length_m > geometry_.min_length())) return {0.0, ForceStatus::too_short};
    if (!(length_m < geometry_.max_length())) return {0.0, ForceStatus::too_long};
    return {settle_held_braid(geometry_, params_, workspace.braid, length_m, gauge_pressure_Pa, velocity_m_per_s, 0.0),
            ForceStatus::ok};
  }

  /// Shortest length with a force [m] (exclusive).
  double min_length_m() const noexcept { return geometry_.min_length(); }
  /// Longest length with a force [m] (exclusive).
  double max_length_m() const noexcept { return geometry_.max_length(); }
  /// The validated parameters.
  const MuscleParams& params() const noexcept { return params_; }
  /// The braid they give.
  const BraidGeometry& geometry() const noexcept { return geometry_; }

 private:
  MuscleParams params_;
  BraidGeometry geometry_;
};

}  // namespace pamkit
