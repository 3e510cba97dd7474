#pragma once
/// \file
/// The catalog effect `sensor_lag` (docs/effects.md).

#include <cmath>
#include <vector>

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

namespace detail {
/// The exact response of tau dy/dt = x - y to an `x` linear between samples, starting settled,
/// written over `x`.
inline void first_order_lag(const std::vector<double>& time_s, std::vector<double>& x, double tau) {
  if (tau == 0.0 || x.empty()) return;
  double y = x.front();
  double previous = x.front();  // the input at the last sample (x is overwritten)
  for (std::size_t k = 1; k < x.size(); ++k) {
    const double decay = std::exp(-(time_s[k] - time_s[k - 1]) / tau);
    const double slope = (x[k] - previous) / (time_s[k] - time_s[k - 1]);
    y = x[k] - slope * tau + (y - previous + slope * tau) * decay;
    previous = x[k];
    x[k] = y;
  }
}
}  // namespace detail

/// sensor_lag: a first-order lag on one measured channel.
struct SensorLagParams {
  static constexpr const char* kName = "sensor_lag";
  static constexpr const char* kDescription =
      "first-order lag of one channel (a TMP36 in still air is slow; a long hose slows a pressure transducer). "
      "In a supplied test on gauge_pressure_Pa, the muscle's pressure lags the transducer's reading (a hose and the "
      "muscle's volume between them). Gives it away: that channel lags its prediction and its swings are "
      "attenuated, more so at higher rates; in a supplied test the force lags the pressure.";
  static constexpr const char* kSignature = "{channel} lags its prediction and swings less";
  static constexpr EffectStage kStage = EffectStage::measurement;
  static constexpr bool kHasChannel = true;
  std::string channel = "temperature_K";
  double time_constant_s = 5.0;  ///< time constant of the lag [s]; 0: none
  template <class V>
  static void for_each_field(V&& visit) {
    visit("time_constant_s", &SensorLagParams::time_constant_s, FieldInfo{"s", 0.0, 1e4, "sensor time constant"},
          EffectFieldInfo{{0.5, 20.0},
                          false,
                          {0.0, 60.0,
                           "a TMP36 in still air: 9-32 s from its thermal resistance and capacity "
                           "(docs/table_3_6.md); transducers and load cells respond in milliseconds"},
                          {FitScale::log, 1e-3, 300.0, 2.0},
                          Resolution::sample_interval,
                          0.0});
  }
};
class SensorLagEffect : public detail::ParametricEffect<SensorLagParams> {
 public:
  /// A strain-gauge load cell and its amplifier settle within milliseconds, and a tensile machine
  /// filters its force at 10 Hz or faster (a time constant of 16 ms at most): a force that lags
  /// by more than a tenth of a second is no instrument's, but a hose's lag of the supplied
  /// pressure seen through the muscle.
  static constexpr double kLoadCellResponse_s = 0.1;

  /// The declared parameters, the time constant's plausible range narrowed on the force.
  std::vector<EffectParameter> parameters() const override {
    std::vector<EffectParameter> out = ParametricEffect::parameters();
    if (params_.channel == "force_N") {
      out.front().plausible_max = kLoadCellResponse_s;
      out.front().plausible_source =
          "a load cell and its amplifier settle within milliseconds; a tensile machine filters its force at "
          "10 Hz or faster (16 ms)";
    }
    return out;
  }

  /// On the pressure of a supplied test the lag sits between the transducer and the muscle:
  /// the reading is the regulator's, and the muscle's gas follows it through the hose.
  bool reads_supplied_pressure() const override { return params_.channel == "gauge_pressure_Pa"; }
  /// A static table's rows are settled (empty `time_s`): the lag has died out.
  void apply_to_supplied_pressure(const std::vector<double>& time_s,
                                  std::vector<double>& gauge_pressure_Pa) const override {
    if (reads_supplied_pressure() && !time_s.empty())
      detail::first_order_lag(time_s, gauge_pressure_Pa, params_.time_constant_s);
  }
  void apply_to_measurement(Measurement& m) const override {
    detail::first_order_lag(m.time_s, m.channel(params_.channel), params_.time_constant_s);
  }
};

}  // namespace pamkit
