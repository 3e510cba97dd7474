#pragma once
/// \file
/// Braid kinematics and volumes of the muscle as functions of its length (thesis 3.1.1-3.1.3,
/// 3.1.9-3.1.11): a cylinder of braided, inextensible fibers between two end cones of fixed
/// slant length, closed by end caps of fixed diameter; or, with flat ends, between two end zones
/// that keep their deflated shape (MuscleBuild::end_zone_m).

#include "pamkit/muscle/build.hpp"

namespace pamkit {

/// Eq. 3.1.9: braid diameter D = Lym sin(theta) / (pi n) of a cylinder whose fibers have
/// length Lym [m] over the cylinder and make n turns, at braid angle theta [rad].
double braid_diameter(double fiber_length_m, double revolutions, double braid_angle_rad);

/// Eq. 3.1.10: cylinder length Lm = Lym cos(theta) [m].
double braid_cylinder_length(double fiber_length_m, double braid_angle_rad);

/// Eq. 3.1.11 inverted: fiber length Lym = sqrt(Lm^2 + (pi n D)^2) [m] of a cylinder of
/// length Lm [m] and diameter D [m] with n turns.
double braid_fiber_length(double cylinder_length_m, double diameter_m, double revolutions);

/// Braid angle [deg] of the deflated build's cylinder, from the axis: tan(theta_0) = pi n D / Lm,
/// the angle a datasheet quotes.
double deflated_braid_angle_deg(const MuscleBuild& build);

/// The fiber revolutions n that give the deflated build braid angle `braid_angle_deg` (eq. 3.1.9
/// with eq. 3.1.10 at the deflated cylinder length, which the end cones fix): a datasheet gives
/// the angle, the model counts turns.
/// \throws InvalidParameter if the angle is outside (0, 90) degrees.
double fiber_revolutions_for_braid_angle(const MuscleBuild& build, double braid_angle_deg);

/// Shape of the muscle at one length, with the derivatives with respect to that length that
/// the force (virtual work) and the gas equation need. Angles in rad, lengths in m, volumes in m^3.
struct MuscleShape {
  double length;             ///< L, between the end caps
  double diameter;           ///< D, braid diameter of the cylinder
  double cylinder_length;    ///< Lm = L - 2 LL
  double cone_length;        ///< LL, axial length of one end: its cone, or a flat end's zone
  double braid_angle;        ///< theta of the cylinder, from the axis (eq. 3.1.9-3.1.10)
  double end_braid_angle;    ///< theta_e at the end cap: sin(theta_e) = (d / D) sin(theta)
  double cone_angle;         ///< beta, inclination of the cone's slant from the axis
  double mean_braid_angle;   ///< theta_a = (theta + theta_e) / 2 (section 3.1.1)
  double total_volume;       ///< eq. 3.1.1, inside the braid, bladder included
  double bladder_volume;     ///< the bladder's rubber: eq. 3.1.3 on the deflated build, conserved
  double gas_volume;         ///< eq. 3.1.2: total minus bladder
  double d_diameter;         ///< dD/dL [1]
  double d_cylinder_length;  ///< dLm/dL [1]
  double d_total_volume;     ///< dV_total/dL [m^2]
  double d_bladder_volume;   ///< dV_bladder/dL [m^2]: 0, the wall conserves its volume
  double d_gas_volume;       ///< dV_gas/dL [m^2]
};

/// How the shape moves with the fibers' length b over the cylinder (fiber compliance,
/// sim/model.hpp): partial derivatives in b at fixed muscle length L, and their own partial
/// derivatives in b and in L, which the fibers' tension's slopes need. At fixed L only the
/// diameter moves with b; the cone's axial length, so the cylinder's, follows the diameter.
struct FiberLengthDerivatives {
  double d_diameter;                  ///< dD/db [1]
  double d_cylinder_length;           ///< dLm/db [1]
  double d_gas_volume;                ///< dV_gas/db = dV_total/db [m^2]: the wall keeps its volume
  double d2_diameter;                 ///< d2D/db2 [1/m]
  double d2_cylinder_length;          ///< d2Lm/db2 [1/m]
  double d2_gas_volume;               ///< d2V_gas/db2 [m]
  double d_diameter_d_length;         ///< d2D/db dL [1/m]
  double d_cylinder_length_d_length;  ///< d2Lm/db dL [1/m]
  double d_gas_volume_d_length;       ///< d2V_gas/db dL [m]
};

/// Which parts of a MuscleShape to compute. The ODE's right-hand side needs the lengths, the
/// volumes and their derivatives; the four angles (an output column, the Newtonian tensions)
/// cost an atan2, two asin and a sin it never uses. Angles left out are NaN, so a misuse shows.
enum class ShapeParts {
  all,                         ///< every field
  kinematics_and_braid_angle,  ///< all but the end, cone and mean angles: what a simulation reports
  kinematics                   ///< all but the four angles: what the ODE's rates need
};

/// Where the last solve of the closure ended, for the next one to start from. Newton's method
/// from the previous diameter extrapolated along dD/dL converges in about two iterations instead
/// of five from the cylinder's guess. Mutable, so it belongs to one caller (a simulation's
/// workspace), never to the const BraidGeometry, which stays safe to share between threads.
struct ShapeHint {
  double length_m = 0.0;    ///< length of the last solve [m]; 0: none yet
  double diameter_m = 0.0;  ///< its braid diameter [m]
  double d_diameter = 0.0;  ///< its dD/dL [1]
};

/// The braid of one muscle build: fixed fiber length and turns, fixed cones. Immutable and
/// cheap to copy; `shape(L)` is safe to call from many threads.
class BraidGeometry {
 public:
  /// \param build validated muscle build; the fiber length is fixed by its deflated length
  ///        and braid diameter.
  /// \throws InvalidParameter if `build` is invalid.
  explicit BraidGeometry(const MuscleBuild& build);

  /// Shape of the muscle at length `length_m`. Solves the cone closure
  /// (pi n D)^2 + (L - 2 LL(D))^2 = Lym^2 for D by bracketed Newton iteration.
  /// \throws InvalidInput if `length_m` is outside `(min_length(), max_length())`.
  MuscleShape shape(double length_m) const;

  /// `shape(length_m)` without the range check, for a caller that checked
  /// `min_length() < length_m < max_length()` itself (RealtimeMuscle, muscle/realtime.hpp):
  /// no error, no allocation. Outside that range the result means nothing.
  MuscleShape shape_unchecked(double length_m) const noexcept;

  /// `shape(length_m)` started from `hint`, which it updates to this solve; `parts` says
  /// whether the angles are computed. The diameter agrees with the cold start's to the Newton
  /// iteration's tolerance (about 1e-14 relative).
  /// \throws InvalidInput if `length_m` is outside `(min_length(), max_length())`.
  MuscleShape shape_from(ShapeHint& hint, double length_m, ShapeParts parts) const;

  /// `shape_from` for fibers of length `fiber_length_m` over the cylinder instead of the build's
  /// (fibers stretched by their tension); its derivatives are at that fiber length. With
  /// `fiber_length_m == fiber_length()` it is `shape_from`, bit for bit.
  /// \throws InvalidInput if `length_m` is outside `(min_length_for_fibers(fiber_length_m),
  ///         max_length_for_fibers(fiber_length_m))`.
  MuscleShape shape_from(ShapeHint& hint, double length_m, double fiber_length_m, ShapeParts parts) const;

  /// The derivatives of `shape`, solved for fibers of length `fiber_length_m`, in that fiber
  /// length: from the closure G(D; L, b) = 0, dD/db = 2 b / G_D, and the geometry's own closed
  /// forms in D (cones of fixed slant, the frusta and cylinder of eq. 3.1.1).
  FiberLengthDerivatives fiber_length_derivatives(const MuscleShape& shape, double fiber_length_m) const noexcept;

  /// Shortest length the model allows [m]: the cones flatten (D = d + 2 Lz) there; with flat
  /// ends the cylinder between the end zones shrinks to nothing.
  double min_length() const { return min_length_; }
  /// Longest length the model allows [m]: the braid closes onto the end diameter.
  double max_length() const { return max_length_; }
  /// The length range of fibers of length `fiber_length_m` over the cylinder [m], as
  /// min_length() and max_length() are the range of the build's fibers.
  double min_length_for_fibers(double fiber_length_m) const noexcept;
  double max_length_for_fibers(double fiber_length_m) const noexcept;
  /// The longest fibers whose braid still reaches the muscle length `length_m` [m]: with end
  /// cones, where the cones lie flat at that length (min_length_for_fibers(b) = L); with flat ends none
  /// (infinity).
  double longest_fiber_length(double length_m) const noexcept;
  /// Fiber length over the cylinder, Lym [m].
  double fiber_length() const { return fiber_length_; }
  /// Cylinder length of the deflated build, the bladder's longitudinal reference [m].
  double deflated_cylinder_length() const { return deflated_cylinder_length_; }
  const MuscleBuild& build() const { return build_; }

 private:
  /// \throws InvalidInput if `length_m` is outside `(min_length(), max_length())`.
  void check_range(double length_m) const;
  /// The shape at a length inside the range of fibers of length `fiber_length_m`, the closure's
  /// Newton iteration started from `hint`.
  MuscleShape solve(ShapeHint& hint, double length_m, double fiber_length_m, ShapeParts parts) const noexcept;

  MuscleBuild build_;
  double fiber_length_;
  double deflated_cylinder_length_;
  double min_length_;
  double max_length_;
  double wall_volume_;  ///< the bladder's rubber [m^3], conserved
};

}  // namespace pamkit

#include "pamkit/muscle/geometry.hxx"
