#pragma once
/// \file
/// Prescribed elongation histories: any sampled trajectory (linear between samples), and the
/// thesis's bench protocol.

#include <cmath>
#include <cstddef>
#include <vector>

#include "pamkit/error.hpp"

namespace pamkit {

/// Elongation [m] against time [s], linear between samples: what a tensile machine's
/// crosshead does. Samples are the simulator's output times too.
class ElongationTrajectory {
 public:
  /// \param time_s strictly increasing sample times [s], at least two
  /// \param elongation_m elongation from the initial length at each time [m], same size
  /// \throws InvalidInput naming the first bad sample (its index and value).
  ElongationTrajectory(std::vector<double> time_s, std::vector<double> elongation_m);

  std::size_t size() const { return time_.size(); }
  const std::vector<double>& time() const { return time_; }
  const std::vector<double>& elongation() const { return elongation_; }
  /// Elongation rate on the segment [t_k, t_{k+1}] [m/s].
  double segment_velocity(std::size_t k) const {
    return (elongation_[k + 1] - elongation_[k]) / (time_[k + 1] - time_[k]);
  }

 private:
  std::vector<double> time_;
  std::vector<double> elongation_;
};

/// The bench protocol of section 3.2.1: `cycles` triangular cycles from zero to
/// `max_elongation_m` and back at `speed_m_per_s`, sampled every `sample_period_s` (the
/// turning points are always samples), with `hold_s` at the top and bottom of each cycle.
/// \throws InvalidInput for non-positive speed, elongation, cycles or period.
ElongationTrajectory thesis_protocol(double max_elongation_m, double speed_m_per_s = 2.5e-3, int cycles = 10,
                                     double sample_period_s = 0.1, double hold_s = 0.0);

inline ElongationTrajectory::ElongationTrajectory(std::vector<double> time_s, std::vector<double> elongation_m)
    : time_(std::move(time_s)), elongation_(std::move(elongation_m)) {
  if (time_.size() != elongation_.size()) {
    throw InvalidInput(
        detail::message("trajectory: ", time_.size(), " times but ", elongation_.size(), " elongations"));
  }
  if (time_.size() < 2) {
    throw InvalidInput(detail::message("trajectory: needs at least 2 samples, got ", time_.size()));
  }
  for (std::size_t k = 0; k < time_.size(); ++k) {
    if (!std::isfinite(time_[k]))
      throw InvalidInput(detail::message("trajectory: time_s[", k, "] = ", time_[k], " is not finite"));
    if (!std::isfinite(elongation_[k])) {
      throw InvalidInput(detail::message("trajectory: elongation_m[", k, "] = ", elongation_[k], " is not finite"));
    }
    if (k > 0 && !(time_[k] > time_[k - 1])) {
      throw InvalidInput(detail::message("trajectory: time_s[", k, "] = ", time_[k], " does not increase (time_s[",
                                         k - 1, "] = ", time_[k - 1], ")"));
    }
  }
}

inline ElongationTrajectory thesis_protocol(double max_elongation_m, double speed_m_per_s, int cycles,
                                            double sample_period_s, double hold_s) {
  if (!(max_elongation_m > 0.0))
    throw InvalidInput(detail::message("thesis_protocol: max_elongation_m = ", max_elongation_m, " must be > 0"));
  if (!(speed_m_per_s > 0.0))
    throw InvalidInput(detail::message("thesis_protocol: speed_m_per_s = ", speed_m_per_s, " must be > 0"));
  if (cycles < 1) throw InvalidInput(detail::message("thesis_protocol: cycles = ", cycles, " must be >= 1"));
  if (!(sample_period_s > 0.0))
    throw InvalidInput(detail::message("thesis_protocol: sample_period_s = ", sample_period_s, " must be > 0"));
  if (!(hold_s >= 0.0)) throw InvalidInput(detail::message("thesis_protocol: hold_s = ", hold_s, " must be >= 0"));

  std::vector<double> t{0.0};
  std::vector<double> e{0.0};
  const double ramp = max_elongation_m / speed_m_per_s;
  // Appends a straight segment from the last sample to (duration later, target), sampled.
  auto segment = [&](double duration, double target) {
    const double t0 = t.back();
    const double e0 = e.back();
    const auto steps = static_cast<long>(std::ceil(duration / sample_period_s - 1e-9));
    for (long i = 1; i <= steps; ++i) {
      const double f = (i == steps) ? 1.0 : static_cast<double>(i) * sample_period_s / duration;
      t.push_back(t0 + f * duration);
      e.push_back(e0 + f * (target - e0));
    }
  };
  for (int c = 0; c < cycles; ++c) {
    segment(ramp, max_elongation_m);
    if (hold_s > 0.0) segment(hold_s, max_elongation_m);
    segment(ramp, 0.0);
    if (hold_s > 0.0) segment(hold_s, 0.0);
  }
  return ElongationTrajectory(std::move(t), std::move(e));
}

}  // namespace pamkit
