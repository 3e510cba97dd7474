#pragma once
/// \file
/// The catalog effect `thermometer`: the TMP36's offset (docs/effects.md).

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

/// thermometer: the temperature reading's offset (the TMP36's accuracy, the ADC's reference).
///
/// Offset only: in a test the gas stays within a degree of ambient, so a gain error of the
/// reading (a reference off by a few percent times ~22 degC) is indistinguishable from an offset.
struct ThermometerParams {
  static constexpr const char* kName = "thermometer";
  static constexpr const char* kDescription =
      "offset of the temperature reading: the TMP36's own accuracy and the ADC reference it is read against "
      "(a 5 V USB supply at 4.8 V shifts 0.75 V by 4 %, about 1.5 degC). Gives it away: the temperature is "
      "off by a constant at rest and through the test, while its swings fit.";
  static constexpr const char* kSignature = "temperature reads off by a constant";
  static constexpr EffectStage kStage = EffectStage::measurement;
  static constexpr const char* kChannel = "temperature_K";
  static constexpr bool kHasChannel = false;
  double offset_K = 1.0;  ///< reading minus the gas temperature [K]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("offset_K", &ThermometerParams::offset_K, FieldInfo{"K", -50.0, 50.0, "temperature reading offset"},
          EffectFieldInfo{{0.5, 2.0},
                          true,
                          {-4.0, 4.0,
                           "TMP36 datasheet: +-2 degC accuracy at 25 degC, plus up to 2 degC from an ADC "
                           "reference (AVCC) a few percent off"},
                          {FitScale::linear, -10.0, 10.0, 0.0},
                          Resolution::any,
                          0.0});
  }
};
class ThermometerEffect : public detail::ParametricEffect<ThermometerParams> {
 public:
  bool reads_samples_alone() const override { return true; }
  void apply_to_measurement(Measurement& m) const override {
    for (double& t : m.temperature_K) t += params_.offset_K;
  }
};

}  // namespace pamkit
