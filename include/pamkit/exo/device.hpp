#pragma once
/// \file
/// The exoskeleton over the gait cycle: the leg's ankle angle through the play to the device,
/// the clutch, the linkage and a spring law to the torque the device adds at the ankle; the
/// inverse (the ideal spring for a share of the biological moment); appendix G.3's script
/// reproduced as printed; and the device's elongation as a trajectory for the muscle's ODE.

#include <cstddef>
#include <optional>
#include <vector>

#include <boost/math/tools/roots.hpp>

#include "pamkit/exo/clutch.hpp"
#include "pamkit/exo/gait.hpp"
#include "pamkit/exo/linkage.hpp"
#include "pamkit/sim/trajectory.hpp"

namespace pamkit::exo {

/// One stride of the device, sample by sample (the GaitCycle's samples).
struct DeviceRun {
  std::vector<double> percent;               ///< percent of the gait cycle [%]
  std::vector<double> ankle_angle_deg;       ///< leg: shank to foot (G.3 testangle) [deg]
  std::vector<double> device_angle_deg;      ///< device: shank strut to foot plate, after play [deg]
  std::vector<int> mode;                     ///< ClutchMode as an integer
  std::vector<double> heel_bar_angle_deg;    ///< psi, heel bar to shank strut [deg]
  std::vector<double> spring_length_m;       ///< anchor to anchor [m]
  std::vector<double> elongation_m;          ///< beyond the block length [m]
  std::vector<double> moment_arm_m;          ///< perpendicular moment arm [m]
  std::vector<double> horizontal_lever_m;    ///< G.3 momentarm(1,:) [m]
  std::vector<double> force_N;               ///< spring force [N]
  std::vector<double> torque_Nm;             ///< plantarflexor torque the device adds at the ankle [N m]
  std::vector<double> biological_torque_Nm;  ///< the GaitCycle's moment [N m]
  std::optional<double> engage_percent;      ///< where the pawl meshed in this stride [%], if it did
  std::optional<double> release_percent;     ///< where the pawl lifted in this stride [%], if it did
};

/// Runs the device along `strides` repeats of `cycle` and returns the last stride, so the
/// clutch's state has settled into its periodic pattern.
/// \param spring any callable double(double elongation_m) -> force [N]
/// \param initial the clutch's mode at the first sample
/// \throws InvalidParameter for bad settings, InvalidInput if strides < 1, and what the spring throws.
template <class SpringLaw>
DeviceRun run_device(const GaitCycle& cycle, const Linkage& linkage, const ClutchParams& clutch, const PlayParams& play,
                     const SpringLaw& spring, int strides = 3, ClutchMode initial = ClutchMode::engaged);

/// Screw settings that suit a gait on a well-fitted device: the engage screw where the pawl
/// meshes `margin_deg` before the most dorsiflexed angle of swing (so it is engaged at heel
/// strike, as in figure 4.12 A), the release screw where it lifts `margin_deg` before the most
/// plantarflexed angle of the stride (push-off, figure 4.12 C). Each switch needs
/// `travel_deg` of rotation (section 4.4).
/// \throws InvalidInput if the gait's range cannot hold both switches.
ClutchParams fit_clutch(const GaitCycle& cycle, double travel_deg = 7.0, double margin_deg = 0.5);

/// The ideal spring of figure 4.7: the force that would give `share` of the biological
/// moment at each stance sample, against the elongation the device has there.
struct IdealSpring {
  std::vector<double> percent;       ///< stance samples where the spring is stretched [%]
  std::vector<double> elongation_m;  ///< elongation [m]
  std::vector<double> force_N;       ///< share x moment / moment arm [N]
  double peak_force_N;               ///< largest force [N]
  double elongation_at_peak_m;       ///< elongation where it occurs [m]
  double max_elongation_m;           ///< largest elongation over stance [m]
  /// Force where the stretching (first) branch reaches `elongation_m`, by linear interpolation;
  /// empty if the device never stretches that far.
  std::optional<double> force_at(double elongation_m) const;
  std::size_t loading_samples;  ///< samples of the stretching branch (the first ones)
};

/// The inverse problem on a run of the device: IdealSpring over the run's engaged, stretched
/// stance samples (before `cycle.toe_off_percent`), for `share` of the biological moment.
/// \throws InvalidInput if share is not in (0, 10] or the run never stretches the spring in stance.
IdealSpring ideal_spring(const DeviceRun& run, double toe_off_percent, double share);

/// Appendix G.3's script as printed, row by row of the data: the heel bar sits on the block
/// except for begin_row < row < end_row (the script's `beginstretch` = 12 and `disengage` = 43,
/// 1-based rows), when it turns with the foot from where it was at begin_row. The script's
/// `engageangle` and `disengageangle` are declared but never used; this is the timing it ran.
struct ScriptKinematics {
  std::vector<double> row;                 ///< 1-based rows 2..size-1, as the script's loop
  std::vector<double> spring_length_m;     ///< `springlength`
  std::vector<double> elongation_m;        ///< `elongation`
  std::vector<double> moment_arm_m;        ///< perpendicular arm, the denominator of `idealforce`
  std::vector<double> horizontal_lever_m;  ///< `momentarm(1,:)`
  std::vector<double> moment_Nm;           ///< `anklemoment` (plantarflexor > 0), scaled to body_mass_kg
  std::vector<double> ideal_force_N;       ///< `idealforce` (rows < toe-off: the script's 1:45), 0 elsewhere
};
ScriptKinematics reproduce_g3_script(const GaitData& data, const Linkage& linkage, double body_mass_kg,
                                     int begin_row = 12, int end_row = 43, int ideal_rows = 45);

/// The muscle's elongation over `strides` strides of `stride_period_s` seconds: the run's
/// spring elongation plus `pretension_m`, periodic, one sample per run sample, and a final
/// sample closing the last stride. The trajectory the Simulator drives the muscle along.
/// \throws InvalidInput for a period <= 0, strides < 1 or pretension < 0.
ElongationTrajectory walking_trajectory(const DeviceRun& run, double stride_period_s, int strides,
                                        double pretension_m = 0.0);

}  // namespace pamkit::exo

#include "pamkit/exo/device.hxx"
