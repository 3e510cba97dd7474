#pragma once
/// \file
/// D. A. Winter's normal walking data as the thesis printed it in appendix G.3 (a 56.7 kg
/// female subject; hip, shank ("leg") and foot segment angles and the ankle moment, one row
/// per film frame), its gait events, and its resampling to percent of the gait cycle.
///
/// Angle conventions are the script's: a segment angle a [deg] is printed as Winter gives it,
/// and the script turns it into the direction a + 180 deg of hip->knee, knee->ankle and
/// ankle->ball of foot in a frame with x forward (direction of walking) and y up. So the shank
/// strut points from the ankle towards the knee at leg_deg, and the angle between the shank
/// strut and the foot arm is the script's `testangle` = leg - foot + 180 deg (eq. below).

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "pamkit/error.hpp"

namespace pamkit::exo {

/// Body mass of Winter's subject [kg] (appendix G.3: "56.7 Kg female individual").
inline constexpr double kWinterSubjectMass_kg = 56.7;

/// Frames of gait data as printed: consecutive frames, angles [deg], moment [N m].
class GaitData {
 public:
  /// \param ankle_moment_Nm the moment as printed (Winter's sign: plantarflexor < 0)
  /// \param subject_mass_kg body mass of the subject the moment was measured on [kg]
  /// \throws InvalidInput naming the first bad column or row (sizes differ, fewer than 3 rows,
  ///         frames not consecutive, a value not finite, a mass <= 0).
  GaitData(std::vector<double> frame, std::vector<double> hip_deg, std::vector<double> leg_deg,
           std::vector<double> foot_deg, std::vector<double> ankle_moment_Nm,
           double subject_mass_kg = kWinterSubjectMass_kg);

  std::size_t size() const { return frame_.size(); }
  const std::vector<double>& frame() const { return frame_; }
  const std::vector<double>& hip_deg() const { return hip_; }
  const std::vector<double>& leg_deg() const { return leg_; }
  const std::vector<double>& foot_deg() const { return foot_; }
  const std::vector<double>& ankle_moment_Nm() const { return moment_; }
  double subject_mass_kg() const { return mass_; }

  /// Angle between the shank strut and the foot arm at row `row` [deg]: G.3's `testangle`,
  /// legangle - pi + (2 pi - footangle) with the script's +pi offsets, = leg - foot + 180.
  /// It falls when the ankle dorsiflexes.
  double ankle_angle_deg(std::size_t row) const { return leg_[row] - foot_[row] + 180.0; }

 private:
  std::vector<double> frame_, hip_, leg_, foot_, moment_;
  double mass_;
};

/// Gait events found in the data (frame numbers as printed, fractional where interpolated).
struct GaitEvents {
  double heel_strike_frame;  ///< first frame of the stride [frame]
  double toe_off_frame;      ///< end of stance [frame]
  double stride_frames;      ///< frames in one stride, heel strike to heel strike [frame]
  /// Stance as a share of the stride [%].
  double stance_percent() const { return 100.0 * (toe_off_frame - heel_strike_frame) / stride_frames; }
};

/// Finds the gait events from the data alone:
///  - stride: the lag (whole frames) at which hip, shank and foot angles repeat best (least
///    RMS difference over the rows the lag leaves), since the printed data span more than one
///    stride;
///  - heel strike: the first frame whose moment turns dorsiflexor (printed > 0) after a
///    non-dorsiflexor frame: the tibialis anterior lowering the foot after heel contact;
///  - toe-off: the first frame after the stance peak of the plantarflexor moment where that
///    moment has ended (printed >= 0).
/// \throws InvalidInput if an event cannot be found.
GaitEvents detect_gait_events(const GaitData& data);

/// One stride resampled at evenly spaced percent of the gait cycle, 0 % at heel strike.
struct GaitCycle {
  std::vector<double> percent;          ///< percent of the gait cycle [%], n points in [0, 100)
  std::vector<double> hip_deg;          ///< thigh segment angle [deg]
  std::vector<double> leg_deg;          ///< shank segment angle = direction of the shank strut [deg]
  std::vector<double> foot_deg;         ///< foot segment angle [deg]
  std::vector<double> ankle_angle_deg;  ///< shank strut to foot arm (G.3 `testangle`) [deg]
  std::vector<double> moment_Nm;        ///< biological ankle moment, plantarflexor > 0, scaled to body_mass_kg [N m]
  double body_mass_kg;                  ///< the body mass the moment is scaled to [kg]
  double toe_off_percent;               ///< end of stance [%]
  std::size_t size() const { return percent.size(); }
};

/// Resamples one stride (from `events.heel_strike_frame`, `events.stride_frames` long) at
/// `points` evenly spaced percents, linearly between frames. The moment changes sign
/// (plantarflexor > 0, as the script's `anklemoment = -anklemomentraw`) and scales with body
/// mass, moment/mass being what Winter's normalised data keep constant (the thesis scales to
/// 86 kg for figure 4.7).
/// \throws InvalidInput if points < 2, the mass is not > 0 or the stride runs past the data.
GaitCycle resample_cycle(const GaitData& data, const GaitEvents& events, std::size_t points, double body_mass_kg);

/// The cycle with the ankle angle's excursion scaled to `range_deg` about the middle of its
/// range, everything else kept: the walking trials measured the wearer's ankle range falling
/// from about 33 deg to 15 deg with the device on (section 5.3, figure 5.4). Only the
/// shank-to-foot angle drives the device, so this is what the clutch and spring see.
/// \throws InvalidInput if range_deg is not > 0 or the cycle's angle does not vary.
GaitCycle with_ankle_range(GaitCycle cycle, double range_deg);

/// Winter's data as appendix G.3 prints it (84 frames, 56.7 kg subject), embedded at build time
/// from data/gait/winter_g3.csv (its columns: frame, hip_deg, leg_deg, foot_deg, ankle_moment_Nm).
GaitData winter_appendix_g3();

}  // namespace pamkit::exo

#include "pamkit/exo/gait.hxx"
