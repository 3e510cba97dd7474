#pragma once

#include <algorithm>
#include <cmath>

#include "pamkit/error.hpp"

namespace pamkit::logger {

inline PressureFit fit_pressure(const std::vector<double>& applied_psi, const std::vector<double>& measured_V) {
  using pamkit::detail::message;
  if (applied_psi.size() != measured_V.size()) {
    throw InvalidInput(message("pressure calibration: ", applied_psi.size(), " applied pressures but ",
                               measured_V.size(), " measured voltages"));
  }
  const std::size_t n = applied_psi.size();
  if (n < 2) throw InvalidInput(message("pressure calibration: needs at least 2 points, got ", n));
  double mean_v = 0, mean_p = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(applied_psi[i]) || !std::isfinite(measured_V[i])) {
      throw InvalidInput(message("pressure calibration: point ", i + 1, " (", applied_psi[i], " psi, ", measured_V[i],
                                 " V) is not finite"));
    }
    mean_v += measured_V[i] / n;
    mean_p += applied_psi[i] * kKilopascalPerPsi / n;
  }
  double svv = 0, svp = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dv = measured_V[i] - mean_v;
    svv += dv * dv;
    svp += dv * (applied_psi[i] * kKilopascalPerPsi - mean_p);
  }
  // One ADC count at 5 V is 4.9 mV: voltages spread less than that cannot fix a slope.
  if (std::sqrt(svv / n) < 5e-3) {
    throw InvalidInput(message("pressure calibration: the measured voltages hardly differ (spread ", std::sqrt(svv / n),
                               " V); were they filled in?"));
  }
  PressureFit fit;
  fit.kPa_per_V = svp / svv;
  fit.offset_kPa = mean_p - fit.kPa_per_V * mean_v;
  for (std::size_t i = 0; i < n; ++i) {
    const double residual = fit.offset_kPa + fit.kPa_per_V * measured_V[i] - applied_psi[i] * kKilopascalPerPsi;
    fit.max_residual_kPa = std::max(fit.max_residual_kPa, std::abs(residual));
  }
  return fit;
}

}  // namespace pamkit::logger
