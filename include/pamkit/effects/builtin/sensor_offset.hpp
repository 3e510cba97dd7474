#pragma once
/// \file
/// The catalog effect `sensor_offset` (docs/effects.md).

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
  static constexpr const char* kChannel = "gauge_pressure_Pa";
  static constexpr bool kHasChannel = false;
  double offset_Pa = 5e3;  ///< reading at zero gauge pressure [Pa]
  double gain = 1.0;       ///< reading per true pascal [1]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("offset_Pa", &SensorOffsetParams::offset_Pa, FieldInfo{"Pa", -500e3, 500e3, "pressure offset"},
          EffectFieldInfo{{-12e3, 12e3},
                          false,
                          {-15e3, 15e3,
                           "2 % of the 61CP transducer's 0-100 psi span (689 kPa) after a calibration by hand "
                           "(appendix B)"},
                          {FitScale::linear, -100e3, 100e3, 0.0},
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
  void apply_to_supplied_pressure(const std::vector<double>&, std::vector<double>& gauge_pressure_Pa) const override {
    for (double& p : gauge_pressure_Pa) p = (p - params_.offset_Pa) / params_.gain;
  }
  bool reads_samples_alone() const override { return true; }
  void apply_to_measurement(Measurement& m) const override {
    for (double& p : m.gauge_pressure_Pa) p = params_.gain * p + params_.offset_Pa;
  }
};

}  // namespace pamkit
