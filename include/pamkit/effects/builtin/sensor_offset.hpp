#pragma once
/// \file
/// The catalog effect `sensor_offset` (DESIGN.md, "The effect catalog").

#include <vector>

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

/// sensor_offset: offset and gain error of the pressure calibration.
struct SensorOffsetParams {
  static constexpr const char* kName = "sensor_offset";
  static constexpr const char* kDescription =
      "offset and gain error of the pressure transducer's calibration (appendix B's linear fit, redone by hand). "
      "Gives it away: a constant offset, or a residual proportional to the pressure, at every rate and in holds.";
  static constexpr const char* kSignature = "pressure reads off by a constant or a scale";
  static constexpr EffectStage kStage = EffectStage::measurement;
  static constexpr const char* kChannel = "pressure_kPa";
  static constexpr bool kHasChannel = false;
  double offset_kPa = 5.0;  ///< reading at zero gauge pressure [kPa]
  double gain = 1.0;        ///< reading per true kPa [1]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("offset_kPa", &SensorOffsetParams::offset_kPa, FieldInfo{"kPa", -500.0, 500.0, "pressure offset"},
          EffectFieldInfo{{-12.0, 12.0},
                          false,
                          {-15.0, 15.0,
                           "2 % of the 61CP transducer's 0-100 psi span (689 kPa) after a calibration by hand "
                           "(appendix B)"},
                          {FitScale::linear, -100.0, 100.0, 0.0},
                          Resolution::any,
                          0.0});
    visit("gain", &SensorOffsetParams::gain, FieldInfo{"1", 0.1, 10.0, "pressure gain"},
          EffectFieldInfo{{0.93, 1.07},
                          false,
                          {0.9, 1.1, "a calibration line through appendix B's points off by at most 10 % in slope"},
                          {FitScale::linear, 0.5, 1.5, 1.0},
                          Resolution::any,
                          1.0});
  }
};
class SensorOffsetEffect : public detail::ParametricEffect<SensorOffsetParams> {
 public:
  /// In a supplied test the transducer's reading is the model's input: the true pressure is
  /// the reading with the calibration error undone, and the reported channel is read again.
  bool reads_supplied_pressure() const override { return true; }
  void apply_to_supplied_pressure(const std::vector<double>&, std::vector<double>& pressure_kPa) const override {
    for (double& p : pressure_kPa) p = (p - params_.offset_kPa) / params_.gain;
  }
  void apply_to_measurement(Measurement& m) const override {
    for (double& p : m.pressure_kPa) p = params_.gain * p + params_.offset_kPa;
  }
};

}  // namespace pamkit
