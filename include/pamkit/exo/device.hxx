#pragma once
// Bodies of include/pamkit/exo/device.hpp.

#include <algorithm>
#include <cstdint>
#include <limits>

namespace pamkit::exo {

template <class SpringLaw>
DeviceRun run_device(const GaitCycle& cycle, const Linkage& linkage, const ClutchParams& clutch_params,
                     const PlayParams& play, const SpringLaw& spring, int strides, ClutchMode initial) {
  play.validate();
  if (strides < 1) throw InvalidInput(pamkit::detail::message("run_device: strides = ", strides, " must be >= 1"));
  if (cycle.size() < 2) throw InvalidInput("run_device: the gait cycle has fewer than 2 samples");
  Clutch clutch(clutch_params, initial);
  Backlash backlash(play.dead_zone_deg);
  const double block = linkage.params().block_angle_deg;
  const double compliance = play.compliance_deg_per_Nm;
  // Torque the spring puts on the foot when the ratchet holds the heel bar `stretch` degrees
  // off the block; at zero stretch the block carries any pre-tension, not the foot.
  auto torque_at = [&](double stretch) {
    if (!(stretch > 0.0)) return 0.0;
    const LinkagePose pose = linkage.pose(block + stretch);
    return spring(pose.spring_length_m - linkage.min_spring_length()) * pose.moment_arm_m;
  };

  DeviceRun run;
  ClutchMode previous = initial;
  for (int s = 0; s < strides; ++s) {
    const bool last = s + 1 == strides;
    for (std::size_t k = 0; k < cycle.size(); ++k) {
      const double leg_side = backlash.step(cycle.ankle_angle_deg[k]);
      double angle = leg_side;
      // Straps and shoe give under the device's torque, which pushes the foot plate towards
      // plantarflexion: the device angle solves angle = leg_side + c torque(angle). The
      // torque falls as the angle rises, so the root is bracketed by [leg_side, reference].
      Clutch trial = clutch;
      if (compliance > 0.0 && trial.step(leg_side) == ClutchMode::engaged && trial.stretch_deg(leg_side) > 0.0) {
        const double reference = trial.reference_deg();
        auto residual = [&](double a) { return a - leg_side - compliance * torque_at(reference - a); };
        const double low = residual(leg_side);
        if (low < 0.0) {  // a spring law that pushes (force <= 0) leaves the straps unloaded
          std::uintmax_t iterations = 100;
          angle = boost::math::tools::toms748_solve(residual, leg_side, reference, low, residual(reference),
                                                    boost::math::tools::eps_tolerance<double>(40), iterations)
                      .second;
        }
      }
      const ClutchMode mode = clutch.step(angle);
      const double stretch = clutch.stretch_deg(angle);
      if (last) {
        const double percent = cycle.percent[k];
        // A switch that turns back (releasing -> engaged, engaging -> disengaged) is no event.
        const bool meshed =
            mode == ClutchMode::engaged && (previous == ClutchMode::engaging || previous == ClutchMode::disengaged);
        const bool lifted =
            mode == ClutchMode::disengaged && (previous == ClutchMode::releasing || previous == ClutchMode::engaged);
        if (meshed && !run.engage_percent) run.engage_percent = percent;
        if (lifted && !run.release_percent) run.release_percent = percent;
        const LinkagePose pose = linkage.pose(block + stretch);
        const double elongation = pose.spring_length_m - linkage.min_spring_length();
        const double force = stretch > 0.0 ? spring(elongation) : 0.0;
        run.percent.push_back(percent);
        run.ankle_angle_deg.push_back(cycle.ankle_angle_deg[k]);
        run.device_angle_deg.push_back(angle);
        run.mode.push_back(static_cast<int>(mode));
        run.heel_bar_angle_deg.push_back(pose.heel_bar_angle_deg);
        run.spring_length_m.push_back(pose.spring_length_m);
        run.elongation_m.push_back(elongation);
        run.moment_arm_m.push_back(pose.moment_arm_m);
        run.horizontal_lever_m.push_back(linkage.horizontal_lever_m(pose.heel_bar_angle_deg, cycle.leg_deg[k]));
        run.force_N.push_back(force);
        run.torque_Nm.push_back(force * pose.moment_arm_m);
        run.biological_torque_Nm.push_back(cycle.moment_Nm[k]);
      }
      previous = mode;
    }
  }
  return run;
}

inline ClutchParams fit_clutch(const GaitCycle& cycle, double travel_deg, double margin_deg) {
  if (cycle.size() < 2) throw InvalidInput("fit_clutch: the gait cycle has fewer than 2 samples");
  double swing_min = std::numeric_limits<double>::infinity();
  double stride_max = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < cycle.size(); ++k) {
    if (cycle.percent[k] >= cycle.toe_off_percent) swing_min = std::min(swing_min, cycle.ankle_angle_deg[k]);
    stride_max = std::max(stride_max, cycle.ankle_angle_deg[k]);
  }
  ClutchParams p;
  p.switching_travel_deg = travel_deg;
  p.engage_angle_deg = swing_min + travel_deg + margin_deg;
  p.release_angle_deg = stride_max - travel_deg - margin_deg;
  if (!(p.release_angle_deg > p.engage_angle_deg)) {
    throw InvalidInput(pamkit::detail::message("fit_clutch: the gait's range (swing minimum ", swing_min,
                                               " deg, maximum ", stride_max, " deg) cannot hold two switches of ",
                                               travel_deg, " deg"));
  }
  p.validate();
  return p;
}

inline std::optional<double> IdealSpring::force_at(double e) const {
  for (std::size_t k = 1; k < loading_samples; ++k) {
    const double e0 = elongation_m[k - 1];
    const double e1 = elongation_m[k];
    if (e0 <= e && e <= e1 && e1 > e0) return force_N[k - 1] + (force_N[k] - force_N[k - 1]) * (e - e0) / (e1 - e0);
  }
  return std::nullopt;
}

inline IdealSpring ideal_spring(const DeviceRun& run, double toe_off_percent, double share) {
  if (!(share > 0.0 && share <= 10.0))
    throw InvalidInput(pamkit::detail::message("ideal_spring: share = ", share, " must be in (0, 10]"));
  IdealSpring ideal{};
  for (std::size_t k = 0; k < run.percent.size(); ++k) {
    if (run.percent[k] >= toe_off_percent) break;
    if (run.mode[k] != static_cast<int>(ClutchMode::engaged) || !(run.elongation_m[k] > 0.0)) continue;
    ideal.percent.push_back(run.percent[k]);
    ideal.elongation_m.push_back(run.elongation_m[k]);
    ideal.force_N.push_back(share * run.biological_torque_Nm[k] / run.moment_arm_m[k]);
  }
  if (ideal.percent.empty()) throw InvalidInput("ideal_spring: the device never stretches the spring in stance");
  const auto peak = std::max_element(ideal.force_N.begin(), ideal.force_N.end()) - ideal.force_N.begin();
  const auto stretch =
      std::max_element(ideal.elongation_m.begin(), ideal.elongation_m.end()) - ideal.elongation_m.begin();
  ideal.peak_force_N = ideal.force_N[static_cast<std::size_t>(peak)];
  ideal.elongation_at_peak_m = ideal.elongation_m[static_cast<std::size_t>(peak)];
  ideal.max_elongation_m = ideal.elongation_m[static_cast<std::size_t>(stretch)];
  ideal.loading_samples = static_cast<std::size_t>(stretch) + 1;
  return ideal;
}

inline ScriptKinematics reproduce_g3_script(const GaitData& data, const Linkage& linkage, double body_mass_kg,
                                            int begin_row, int end_row, int ideal_rows) {
  const int rows = static_cast<int>(data.size());
  if (begin_row < 1 || begin_row >= rows || end_row <= begin_row || end_row > rows) {
    throw InvalidInput(pamkit::detail::message("reproduce_g3_script: rows begin ", begin_row, ", end ", end_row,
                                               " must satisfy 1 <= begin < end <= ", rows));
  }
  if (!(body_mass_kg > 0.0))
    throw InvalidInput(pamkit::detail::message("reproduce_g3_script: body_mass_kg = ", body_mass_kg, " must be > 0"));
  const double block = linkage.params().block_angle_deg;
  const double at_begin = data.ankle_angle_deg(static_cast<std::size_t>(begin_row - 1));
  const double scale = -body_mass_kg / data.subject_mass_kg();
  ScriptKinematics out;
  for (int row = 2; row <= rows - 1; ++row) {  // the script's `for i=2:83`
    const auto i = static_cast<std::size_t>(row - 1);
    // Engaged, the heel bar keeps the angle to the foot it had at `beginstretch`
    // (footheelangle); its angle to the shank then grows as the ankle dorsiflexes.
    const double psi = (row > begin_row && row < end_row) ? block + at_begin - data.ankle_angle_deg(i) : block;
    const LinkagePose pose = linkage.pose(psi);
    const double moment = scale * data.ankle_moment_Nm()[i];
    out.row.push_back(row);
    out.spring_length_m.push_back(pose.spring_length_m);
    out.elongation_m.push_back(pose.spring_length_m - linkage.min_spring_length());
    out.moment_arm_m.push_back(pose.moment_arm_m);
    out.horizontal_lever_m.push_back(linkage.horizontal_lever_m(psi, data.leg_deg()[i]));
    out.moment_Nm.push_back(moment);
    out.ideal_force_N.push_back(row <= ideal_rows ? moment / pose.moment_arm_m : 0.0);
  }
  return out;
}

inline ElongationTrajectory walking_trajectory(const DeviceRun& run, double stride_period_s, int strides,
                                               double pretension_m) {
  if (!(stride_period_s > 0.0))
    throw InvalidInput(
        pamkit::detail::message("walking_trajectory: stride_period_s = ", stride_period_s, " must be > 0"));
  if (strides < 1)
    throw InvalidInput(pamkit::detail::message("walking_trajectory: strides = ", strides, " must be >= 1"));
  if (!(pretension_m >= 0.0))
    throw InvalidInput(pamkit::detail::message("walking_trajectory: pretension_m = ", pretension_m, " must be >= 0"));
  if (run.percent.empty()) throw InvalidInput("walking_trajectory: empty device run");
  std::vector<double> time, elongation;
  for (int s = 0; s < strides; ++s) {
    for (std::size_t k = 0; k < run.percent.size(); ++k) {
      time.push_back(stride_period_s * (s + run.percent[k] / 100.0));
      elongation.push_back(run.elongation_m[k] + pretension_m);
    }
  }
  time.push_back(stride_period_s * strides);
  elongation.push_back(run.elongation_m.front() + pretension_m);
  return ElongationTrajectory(std::move(time), std::move(elongation));
}

}  // namespace pamkit::exo
