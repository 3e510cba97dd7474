#pragma once

#include "pamkit/exo/winter_g3_table.hpp"
// Bodies of include/pamkit/exo/gait.hpp.

#include <algorithm>
#include <array>

namespace pamkit::exo {

inline GaitData::GaitData(std::vector<double> frame, std::vector<double> hip_deg, std::vector<double> leg_deg,
                          std::vector<double> foot_deg, std::vector<double> ankle_moment_Nm, double subject_mass_kg)
    : frame_(std::move(frame)),
      hip_(std::move(hip_deg)),
      leg_(std::move(leg_deg)),
      foot_(std::move(foot_deg)),
      moment_(std::move(ankle_moment_Nm)),
      mass_(subject_mass_kg) {
  const std::array<std::pair<const char*, const std::vector<double>*>, 5> columns{{{"frame", &frame_},
                                                                                   {"hip_deg", &hip_},
                                                                                   {"leg_deg", &leg_},
                                                                                   {"foot_deg", &foot_},
                                                                                   {"ankle_moment_Nm", &moment_}}};
  if (!(mass_ > 0.0) || !std::isfinite(mass_)) {
    throw InvalidInput(detail::message("GaitData: subject_mass_kg = ", mass_, " must be > 0"));
  }
  for (const auto& [name, column] : columns) {
    if (column->size() != frame_.size()) {
      throw InvalidInput(
          detail::message("GaitData: column ", name, " has ", column->size(), " rows, frame has ", frame_.size()));
    }
    for (std::size_t i = 0; i < column->size(); ++i) {
      if (!std::isfinite((*column)[i]))
        throw InvalidInput(detail::message("GaitData: ", name, "[", i, "] is not finite"));
    }
  }
  if (frame_.size() < 3) throw InvalidInput(detail::message("GaitData: needs at least 3 frames, got ", frame_.size()));
  for (std::size_t i = 1; i < frame_.size(); ++i) {
    if (frame_[i] != frame_[i - 1] + 1.0) {
      throw InvalidInput(detail::message("GaitData: frame[", i, "] = ", frame_[i], " does not follow frame[", i - 1,
                                         "] = ", frame_[i - 1], " (frames must be consecutive)"));
    }
  }
}

inline GaitEvents detect_gait_events(const GaitData& data) {
  const std::size_t n = data.size();
  const auto& m = data.ankle_moment_Nm();
  // Stride: the RMS difference between the angles and themselves `lag` frames later rises
  // to a maximum near half a stride and falls to its least at one stride. A sixth of the rows
  // must overlap, so that a long lag cannot win on a handful of rows (G.3 prints 84 frames,
  // a stride and a fifth).
  std::vector<double> rms(n - n / 6 + 1, 0.0);
  for (std::size_t lag = 1; lag < rms.size(); ++lag) {
    double sum = 0.0;
    for (std::size_t i = 0; i + lag < n; ++i) {
      const double dh = data.hip_deg()[i + lag] - data.hip_deg()[i];
      const double dl = data.leg_deg()[i + lag] - data.leg_deg()[i];
      const double df = data.foot_deg()[i + lag] - data.foot_deg()[i];
      sum += dh * dh + dl * dl + df * df;
    }
    rms[lag] = std::sqrt(sum / static_cast<double>(n - lag));
  }
  const auto worst = std::max_element(rms.begin() + 1, rms.end());
  const auto best = std::min_element(worst, rms.end());
  if (worst == rms.end() - 1 || best == worst || *best > 0.25 * *worst) {
    throw InvalidInput("detect_gait_events: the angles never repeat: the data do not span a stride");
  }
  const auto stride = static_cast<std::size_t>(best - rms.begin());
  std::size_t heel = n;
  for (std::size_t i = 1; i < n; ++i) {
    if (m[i] > 0.0 && m[i - 1] <= 0.0) {
      heel = i;
      break;
    }
  }
  if (heel == n) throw InvalidInput("detect_gait_events: no heel strike (the moment never turns dorsiflexor)");
  const std::size_t stance_end = std::min(n, heel + stride);
  const auto peak = static_cast<std::size_t>(
      std::min_element(m.begin() + static_cast<long>(heel), m.begin() + static_cast<long>(stance_end)) - m.begin());
  std::size_t toe = n;
  for (std::size_t i = peak; i < stance_end; ++i) {
    if (m[i] >= 0.0) {
      toe = i;
      break;
    }
  }
  if (toe == n) throw InvalidInput("detect_gait_events: no toe-off (the plantarflexor moment never ends)");
  return {data.frame()[heel], data.frame()[toe], static_cast<double>(stride)};
}

inline GaitCycle resample_cycle(const GaitData& data, const GaitEvents& events, std::size_t points,
                                double body_mass_kg) {
  if (points < 2) throw InvalidInput(detail::message("resample_cycle: points = ", points, " must be >= 2"));
  if (!(body_mass_kg > 0.0) || !std::isfinite(body_mass_kg)) {
    throw InvalidInput(detail::message("resample_cycle: body_mass_kg = ", body_mass_kg, " must be > 0"));
  }
  const double first = data.frame().front();
  const double last = data.frame().back();
  if (events.heel_strike_frame < first || events.heel_strike_frame + events.stride_frames > last ||
      !(events.stride_frames > 0.0)) {
    throw InvalidInput(detail::message("resample_cycle: the stride from frame ", events.heel_strike_frame, " over ",
                                       events.stride_frames, " frames runs outside the data (frames ", first, " to ",
                                       last, ")"));
  }
  auto at = [&](const std::vector<double>& column, double frame) {
    const double x = frame - first;
    const auto i = std::min(static_cast<std::size_t>(x), data.size() - 2);
    const double f = x - static_cast<double>(i);
    return column[i] + f * (column[i + 1] - column[i]);
  };
  GaitCycle c;
  c.body_mass_kg = body_mass_kg;
  c.toe_off_percent = 100.0 * (events.toe_off_frame - events.heel_strike_frame) / events.stride_frames;
  const double scale = -body_mass_kg / data.subject_mass_kg();
  for (std::size_t k = 0; k < points; ++k) {
    const double percent = 100.0 * static_cast<double>(k) / static_cast<double>(points);
    const double frame = events.heel_strike_frame + events.stride_frames * percent / 100.0;
    c.percent.push_back(percent);
    c.hip_deg.push_back(at(data.hip_deg(), frame));
    c.leg_deg.push_back(at(data.leg_deg(), frame));
    c.foot_deg.push_back(at(data.foot_deg(), frame));
    c.ankle_angle_deg.push_back(c.leg_deg.back() - c.foot_deg.back() + 180.0);
    c.moment_Nm.push_back(scale * at(data.ankle_moment_Nm(), frame));
  }
  return c;
}

inline GaitCycle with_ankle_range(GaitCycle cycle, double range_deg) {
  if (!(range_deg > 0.0) || !std::isfinite(range_deg)) {
    throw InvalidInput(detail::message("with_ankle_range: range_deg = ", range_deg, " must be > 0"));
  }
  const auto [low, high] = std::minmax_element(cycle.ankle_angle_deg.begin(), cycle.ankle_angle_deg.end());
  const double middle = 0.5 * (*low + *high);
  const double scale = range_deg / (*high - *low);
  if (!std::isfinite(scale)) throw InvalidInput("with_ankle_range: the cycle's ankle angle does not vary");
  for (double& angle : cycle.ankle_angle_deg) angle = middle + scale * (angle - middle);
  return cycle;
}

inline GaitData winter_appendix_g3() {
  std::vector<double> frame, hip, leg, foot, moment;
  for (const auto& row : data::kWinterAppendixG3) {
    frame.push_back(row[0]);
    hip.push_back(row[1]);
    leg.push_back(row[2]);
    foot.push_back(row[3]);
    moment.push_back(row[4]);
  }
  return GaitData(std::move(frame), std::move(hip), std::move(leg), std::move(foot), std::move(moment),
                  kWinterSubjectMass_kg);
}

}  // namespace pamkit::exo
