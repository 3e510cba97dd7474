#pragma once
/// \file
/// The timing mechanism of section 4.4 (a ratchet and pawl) as a hybrid state machine, and
/// the play between the leg and the device that fooled it in the walking trials (chapter 5).
///
/// Angles are the angle between the shank strut and the foot arm (G.3 `testangle`,
/// exo/gait.hpp); it falls when the ankle dorsiflexes.
///
/// Modes (figure 4.12):
///  - disengaged: the pawl is held off the gear, the heel bar rests on the stopper block, the
///    foot rotates freely (swing);
///  - engaging: dorsiflexion past the engage screw pushes the engagement arm along the pawl's
///    cam; after `switching_travel_deg` more the pawl meshes (A);
///  - engaged: the ratchet locks the heel bar to the foot against dorsiflexion, so the spring
///    stretches, and lets it slip the other way (the foot slapping flat after heel strike, B);
///  - releasing: plantarflexion past the release screw pushes the arm the other way; after
///    `switching_travel_deg` more the pawl is lifted (C).
/// While switching the mechanism carries no torque (section 5.4.1: "During this rotation the
/// mechanism is unable to transmit a torque"). If the angle turns back before the travel is
/// complete the pawl's spring (section 4.4) returns the arm, and the mode is what it was.

#include <algorithm>
#include <cmath>

#include "pamkit/fields.hpp"

namespace pamkit::exo {

/// The mechanism's settings.
struct ClutchParams {
  static constexpr const char* kName = "ClutchParams";

  double engage_angle_deg = 111.0;  ///< where dorsiflexion starts engaging [deg] (G.3 `engageangle`, the engage screw)
  double release_angle_deg =
      138.0;  ///< where plantarflexion starts releasing [deg] (G.3 `disengageangle`, the release screw)
  double switching_travel_deg =
      7.0;  ///< rotation the arm needs to switch, carrying no torque [deg] (sections 4.4, 5.4.1)

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("engage_angle_deg", &ClutchParams::engage_angle_deg,
          FieldInfo{"deg", 30.0, 180.0, "engage screw: dorsiflexion past it engages (G.3 engageangle)"});
    visit("release_angle_deg", &ClutchParams::release_angle_deg,
          FieldInfo{"deg", 30.0, 180.0, "release screw: plantarflexion past it releases (G.3 disengageangle)"});
    visit("switching_travel_deg", &ClutchParams::switching_travel_deg,
          FieldInfo{"deg", 0.0, 45.0, "travel to switch state (7 deg, section 4.4)"});
  }
  /// \throws InvalidParameter naming the field; also if release_angle_deg is not above
  ///         engage_angle_deg (the two screws would overlap and the pawl could not rest).
  void validate() const {
    validate_fields(*this);
    if (!(release_angle_deg > engage_angle_deg)) {
      throw InvalidParameter(pamkit::detail::message("ClutchParams.release_angle_deg = ", release_angle_deg,
                                                     " deg must be above engage_angle_deg = ", engage_angle_deg,
                                                     " deg"));
    }
  }
};

/// How the device follows the leg: straps over a shoe (section 5.4.1).
struct PlayParams {
  static constexpr const char* kName = "PlayParams";

  double dead_zone_deg = 0.0;          ///< total free play: the leg turns this much before it moves the device [deg]
  double compliance_deg_per_Nm = 0.0;  ///< further give of straps and shoe per N m the device carries [deg/(N m)]

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("dead_zone_deg", &PlayParams::dead_zone_deg, FieldInfo{"deg", 0.0, 90.0, "free play between leg and device"});
    visit("compliance_deg_per_Nm", &PlayParams::compliance_deg_per_Nm,
          FieldInfo{"deg/(N m)", 0.0, 10.0, "strap and shoe compliance"});
  }
  void validate() const { validate_fields(*this); }
};

/// Mode of the mechanism.
enum class ClutchMode { disengaged = 0, engaging = 1, engaged = 2, releasing = 3 };

inline const char* to_string(ClutchMode mode) {
  switch (mode) {
    case ClutchMode::disengaged:
      return "disengaged";
    case ClutchMode::engaging:
      return "engaging";
    case ClutchMode::engaged:
      return "engaged";
    case ClutchMode::releasing:
      return "releasing";
  }
  return "?";
}

/// The mechanism's state: a small value type the device simulation steps along the gait.
class Clutch {
 public:
  /// \param initial mode at the first angle; `engaged` as a wearer dons the device standing,
  ///        the pawl seated by its spring.
  /// \throws InvalidParameter for bad settings.
  explicit Clutch(const ClutchParams& params, ClutchMode initial = ClutchMode::engaged)
      : params_((params.validate(), params)), mode_(initial) {}

  /// Moves the device to angle `device_angle_deg` and returns the new mode. The first call
  /// sets the reference angles.
  ClutchMode step(double device_angle_deg);

  /// Ratchet stretch: how far the foot has dorsiflexed the locked heel bar off the block [deg];
  /// zero unless engaged.
  double stretch_deg(double device_angle_deg) const {
    return mode_ == ClutchMode::engaged ? std::max(0.0, reference_deg_ - device_angle_deg) : 0.0;
  }

  ClutchMode mode() const { return mode_; }
  /// While engaged, the angle at which the heel bar sits on the block: the most plantarflexed
  /// angle since the pawl meshed, as the ratchet slips that way and locks the other [deg].
  double reference_deg() const { return reference_deg_; }

 private:
  ClutchParams params_;
  ClutchMode mode_;
  double reference_deg_ = 0.0;
  bool started_ = false;
};

inline ClutchMode Clutch::step(double angle) {
  if (!started_) {
    started_ = true;
    reference_deg_ = angle;
  }
  const double travel = params_.switching_travel_deg;
  switch (mode_) {
    case ClutchMode::engaged:
      reference_deg_ = std::max(reference_deg_, angle);
      if (angle >= params_.release_angle_deg) mode_ = travel > 0.0 ? ClutchMode::releasing : ClutchMode::disengaged;
      if (mode_ == ClutchMode::releasing && angle >= params_.release_angle_deg + travel) mode_ = ClutchMode::disengaged;
      break;
    case ClutchMode::releasing:
      if (angle < params_.release_angle_deg) {
        mode_ = ClutchMode::engaged;
        reference_deg_ = std::max(reference_deg_, angle);
      } else if (angle >= params_.release_angle_deg + travel) {
        mode_ = ClutchMode::disengaged;
      }
      break;
    case ClutchMode::disengaged:
      if (angle <= params_.engage_angle_deg) mode_ = travel > 0.0 ? ClutchMode::engaging : ClutchMode::engaged;
      if (mode_ == ClutchMode::engaging && angle <= params_.engage_angle_deg - travel) mode_ = ClutchMode::engaged;
      if (mode_ == ClutchMode::engaged) reference_deg_ = angle;
      break;
    case ClutchMode::engaging:
      if (angle > params_.engage_angle_deg) {
        mode_ = ClutchMode::disengaged;
      } else if (angle <= params_.engage_angle_deg - travel) {
        mode_ = ClutchMode::engaged;
        reference_deg_ = angle;
      }
      break;
  }
  return mode_;
}

/// The play between leg and device as a backlash (dead zone): the device angle stays put
/// while the leg moves within the play, and is dragged along once the leg reaches either end.
class Backlash {
 public:
  explicit Backlash(double dead_zone_deg) : half_(0.5 * dead_zone_deg) {}
  /// Device angle [deg] after the leg moves to `ankle_angle_deg`.
  double step(double ankle_angle_deg) {
    if (!started_) {
      started_ = true;
      output_ = ankle_angle_deg;
    }
    output_ = std::clamp(output_, ankle_angle_deg - half_, ankle_angle_deg + half_);
    return output_;
  }

 private:
  double half_;
  double output_ = 0.0;
  bool started_ = false;
};

}  // namespace pamkit::exo
