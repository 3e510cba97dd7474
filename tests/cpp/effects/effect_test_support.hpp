#pragma once
/// \file
/// Shared pieces of the effect tests: the bench tests they run, the catalog, and the few
/// measures the signatures are stated in (loop areas, cycle peaks, bitwise equality).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

#include "pamkit/effects/catalog.hpp"
#include "pamkit/effects/pipeline.hpp"

namespace pamkit_test {

using namespace pamkit;

/// Table C.2, 90 %: PAM 2 at 0.167 m and 236.63 kPa gauge (the transducer's reading) at zero
/// elongation. With the default MuscleParams (PAM 2's build, table C.4; isothermal gas, n = 1).
inline InitialState table_c2_90() { return {0.167, 236.63e3}; }

/// The atmosphere of the default GasParams (table C.4) [Pa].
constexpr double kAtmosphere_Pa = 101e3;

/// The built-in catalog, parsing `spec` as `--effect` does.
inline EffectPtr effect(const std::string& spec) { return EffectCatalog::builtin().parse(spec); }

/// The closed integral of y dx along samples [first, last] (trapezoids): the area of a loop
/// that the samples trace, positive when y is higher while x increases.
inline double loop_area(const std::vector<double>& x, const std::vector<double>& y, std::size_t first,
                        std::size_t last) {
  double area = 0.0;
  for (std::size_t k = first; k < last; ++k) area += 0.5 * (y[k] + y[k + 1]) * (x[k + 1] - x[k]);
  return area;
}

/// Indices of the samples at the largest elongation (the top of each cycle).
inline std::vector<std::size_t> tops(const std::vector<double>& elongation) {
  const double top = *std::max_element(elongation.begin(), elongation.end());
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < elongation.size(); ++k) {
    if (elongation[k] == top) out.push_back(k);
  }
  return out;
}

/// Index of the sample nearest to time `t`.
inline std::size_t sample_at(const std::vector<double>& time, double t) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < time.size(); ++k) {
    if (std::abs(time[k] - t) < std::abs(time[best] - t)) best = k;
  }
  return best;
}

/// The largest element of a non-empty vector.
inline double max_of(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

/// A measurement with `n` samples `dt` apart and temperature_K = f(t); the other channels filled
/// with recognisable values so that any change to them shows.
template <class F>
Measurement synthetic(std::size_t n, double dt, F f) {
  Measurement m;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * dt;
    m.time_s.push_back(t);
    m.elongation_m.push_back(1e-3 * t);
    m.force_N.push_back(100.0 + t);
    m.gauge_pressure_Pa.push_back(200e3 - 1e3 * t);
    m.temperature_K.push_back(f(t));
  }
  return m;
}

/// Bit-for-bit equality (not ==, which takes -0.0 for 0.0).
inline bool identical(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

/// Every channel of two measurements bit for bit.
inline bool identical(const Measurement& a, const Measurement& b) {
  return identical(a.time_s, b.time_s) && identical(a.elongation_m, b.elongation_m) &&
         identical(a.force_N, b.force_N) && identical(a.gauge_pressure_Pa, b.gauge_pressure_Pa) &&
         identical(a.temperature_K, b.temperature_K);
}

/// A simulator tight enough that its global error (~1e-9 relative over these runs) stays
/// far below every tolerance the effect tests check against closed forms.
inline Simulator precise_simulator() {
  SimulatorConfig config;
  config.relative_tolerance = 1e-10;
  config.absolute_tolerance_K = 1e-10;
  return Simulator(config);
}

/// The simulated bench test with `specs` parsed from text.
inline Measurement measure(const MuscleParams& params, const InitialState& initial,
                           const ElongationTrajectory& crosshead, const std::vector<std::string>& specs) {
  std::vector<EffectPtr> effects;
  for (const std::string& spec : specs) effects.push_back(effect(spec));
  return simulate_measurement(params, initial, crosshead, effects, precise_simulator());
}

}  // namespace pamkit_test
