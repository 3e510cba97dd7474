#pragma once
/// \file
/// The 2D linkage of the thesis's ankle exoskeleton (section 4.3, appendix G.3): a shank
/// upright with the proximal spring anchor, a heel bar pivoting at the ankle with the distal
/// anchor, and the spring between them. Everything is computed in the shank's frame, because
/// all the anchors hang off the shank strut and the ankle: the spring depends only on the
/// heel-bar angle psi between the shank strut and the heel bar.
///
/// Shank frame: origin at the ankle (the device's pivot), x along the shank strut towards the
/// knee, y perpendicular to it towards the heel (posterior). The script's lab frame (x forward,
/// y up) maps onto it by a rotation, so lengths and moments are the same in both.

#include <cmath>

#include "pamkit/fields.hpp"

namespace pamkit::exo {

namespace detail {
inline constexpr double kPi = 3.14159265358979323846;
inline double radians(double degrees) { return degrees * kPi / 180.0; }
inline double degrees(double radians) { return radians * 180.0 / kPi; }
}  // namespace detail

/// Dimensions of the device (appendix G.3's parameters as defaults).
struct LinkageParams {
  static constexpr const char* kName = "LinkageParams";

  double upright_length_m =
      0.30;  ///< along the shank strut from the ankle to the upright's end [m] (G.3 `uprightlength`)
  double shank_offset_m =
      0.10;  ///< from the upright, perpendicular and posterior, to the shank anchor [m] (G.3 `shankoffset`)
  double heel_offset_m = 0.17;  ///< from the ankle to the heel anchor along the heel bar [m] (G.3 `heeloffset`)
  double block_angle_deg =
      100.0;  ///< heel bar to shank strut when the bar rests on the stopper block, the spring at its
              ///< minimum length [deg] (G.3 `blockangle`; set by the pre-tension screw, section 4.4)

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("upright_length_m", &LinkageParams::upright_length_m,
          FieldInfo{"m", 0.02, 1.0, "ankle to the upright's end along the shank (G.3 uprightlength)"});
    visit("shank_offset_m", &LinkageParams::shank_offset_m,
          FieldInfo{"m", 0.0, 0.5, "upright to shank anchor, posterior (G.3 shankoffset)"});
    visit("heel_offset_m", &LinkageParams::heel_offset_m,
          FieldInfo{"m", 0.01, 0.5, "ankle to heel anchor (G.3 heeloffset)"});
    visit("block_angle_deg", &LinkageParams::block_angle_deg,
          FieldInfo{"deg", 1.0, 179.0, "heel bar to shank strut on the stopper block (G.3 blockangle)"});
  }

  /// Checks the ranges, then that the spring can close: at the block the two anchors must be
  /// apart and the spring's line must pass on the heel side of the ankle, so that tension
  /// plantarflexes (otherwise the device would push the foot up).
  /// \throws InvalidParameter naming the field.
  void validate() const;
};

/// The linkage at one heel-bar angle.
struct LinkagePose {
  double heel_bar_angle_deg;  ///< psi, heel bar to shank strut [deg]
  double shank_anchor_x_m;    ///< shank anchor in the shank frame [m]
  double shank_anchor_y_m;
  double heel_anchor_x_m;  ///< heel anchor in the shank frame [m]
  double heel_anchor_y_m;
  double spring_length_m;  ///< anchor to anchor [m] (G.3 `springlength`)
  double moment_arm_m;     ///< perpendicular distance from the ankle to the spring's line, > 0 when tension
                           ///< plantarflexes [m]; the denominator of G.3's `idealforce` (fig. 4.3)
};

/// The device's geometry. Immutable.
class Linkage {
 public:
  /// \throws InvalidParameter (see LinkageParams::validate).
  explicit Linkage(const LinkageParams& params);

  /// The pose at heel-bar angle `heel_bar_angle_deg` [deg].
  LinkagePose pose(double heel_bar_angle_deg) const;

  /// Spring length at the block, the shortest the pre-tension screw allows [m] (G.3 `minspring`).
  double min_spring_length() const { return min_length_; }

  /// Spring elongation beyond the block length at heel-bar angle psi [m] (G.3 `elongation`).
  double elongation(double heel_bar_angle_deg) const { return pose(heel_bar_angle_deg).spring_length_m - min_length_; }

  /// G.3's `momentarm(1,:)`: the horizontal distance from the ankle forward of the heel anchor
  /// (the lever of the spring's vertical pull) when the shank strut points at `leg_deg` in the
  /// lab frame [m]. Not the perpendicular moment arm: see docs/exo.md.
  double horizontal_lever_m(double heel_bar_angle_deg, double leg_deg) const {
    return -params_.heel_offset_m * std::cos(detail::radians(leg_deg + heel_bar_angle_deg));
  }

  const LinkageParams& params() const { return params_; }

 private:
  LinkageParams params_;
  double min_length_;
};

inline void LinkageParams::validate() const {
  validate_fields(*this);
  const double b = detail::radians(block_angle_deg);
  const double dx = upright_length_m - heel_offset_m * std::cos(b);
  const double dy = shank_offset_m - heel_offset_m * std::sin(b);
  const double length = std::hypot(dx, dy);
  if (length < 1e-3) {
    throw InvalidParameter(
        pamkit::detail::message("LinkageParams: the anchors coincide at block_angle_deg = ", block_angle_deg,
                                " (spring length ", length, " m): the spring cannot close"));
  }
  // Moment arm at the block: B x u with B the heel anchor and u the unit vector from it to the shank anchor.
  const double arm = (dx * heel_offset_m * std::sin(b) - dy * heel_offset_m * std::cos(b)) / length;
  if (!(arm > 0.0)) {
    throw InvalidParameter(pamkit::detail::message("LinkageParams.block_angle_deg = ", block_angle_deg,
                                                   " deg puts the spring's line in front of the ankle (moment arm ",
                                                   arm, " m): tension would dorsiflex"));
  }
}

inline Linkage::Linkage(const LinkageParams& params) : params_((params.validate(), params)) {
  min_length_ = pose(params_.block_angle_deg).spring_length_m;
}

inline LinkagePose Linkage::pose(double heel_bar_angle_deg) const {
  LinkagePose p{};
  const double psi = detail::radians(heel_bar_angle_deg);
  p.heel_bar_angle_deg = heel_bar_angle_deg;
  p.shank_anchor_x_m = params_.upright_length_m;
  p.shank_anchor_y_m = params_.shank_offset_m;
  p.heel_anchor_x_m = params_.heel_offset_m * std::cos(psi);
  p.heel_anchor_y_m = params_.heel_offset_m * std::sin(psi);
  const double dx = p.shank_anchor_x_m - p.heel_anchor_x_m;
  const double dy = p.shank_anchor_y_m - p.heel_anchor_y_m;
  p.spring_length_m = std::hypot(dx, dy);
  // Tension pulls the heel anchor along u = (dx, dy) / L; its moment about the ankle, taken
  // plantarflexion-positive, is F (u_x B_y - u_y B_x): G.3's
  // forcecomponent(1) momentarm(2) + forcecomponent(2) momentarm(1) in the shank frame.
  p.moment_arm_m = (dx * p.heel_anchor_y_m - dy * p.heel_anchor_x_m) / p.spring_length_m;
  return p;
}

}  // namespace pamkit::exo
