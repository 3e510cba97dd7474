#pragma once
/// \file
/// From the logger's raw counts to physical values (thesis appendix B): the ADC's volts, the
/// 61CP pressure transducer's linear calibration (points every 10 psi from 0 to 80 psi, fitted
/// by least squares) and the TMP36's T = (V - 0.5 V) / (10 mV/degC).

#include <vector>

#include "pamkit/fields.hpp"
#include "pamkit/units.hpp"
#include "pamkit_frame.h"  // PAMKIT_ADC_FULL_SCALE

namespace pamkit::logger {

using units::kKilopascalPerPsi;

/// The conversion of one logger's readings. Pressure is gauge pressure.
struct LoggerCalibration {
  static constexpr const char* kName = "LoggerCalibration";

  double adc_reference_V = 5.0;      ///< ADC reference, the Mega's AVCC (nominally 5 V: measure it) [V]
  double pressure_kPa_per_V = 0.0;   ///< transducer slope, fitted from the calibration points [kPa/V]
  double pressure_offset_kPa = 0.0;  ///< transducer gauge pressure at 0 V [kPa]
  double tmp36_offset_V = 0.5;       ///< TMP36 output at 0 degC [V] (appendix B; TMP36 datasheet)
  double tmp36_V_per_C = 0.010;      ///< TMP36 scale factor [V/degC] (appendix B; TMP36 datasheet)

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("adc_reference_V", &LoggerCalibration::adc_reference_V,
          FieldInfo{"V", 1.0, 5.5, "ADC reference voltage (AVCC of the Mega)"});
    visit("pressure_kPa_per_V", &LoggerCalibration::pressure_kPa_per_V,
          FieldInfo{"kPa/V", -1e5, 1e5, "pressure transducer slope (appendix B linear fit)"});
    visit("pressure_offset_kPa", &LoggerCalibration::pressure_offset_kPa,
          FieldInfo{"kPa", -1e5, 1e5, "pressure transducer gauge pressure at 0 V"});
    visit("tmp36_offset_V", &LoggerCalibration::tmp36_offset_V, FieldInfo{"V", 0.0, 2.0, "TMP36 output at 0 degC"});
    visit("tmp36_V_per_C", &LoggerCalibration::tmp36_V_per_C, FieldInfo{"V/degC", 1e-4, 1.0, "TMP36 scale factor"});
  }

  /// \throws InvalidParameter naming the field out of range.
  void validate() const { validate_fields(*this); }

  /// Volts at the pin for a mean conversion [counts]: ATmega2560 datasheet, ADC = Vin 1024 / Vref.
  double volts(double mean_counts) const { return mean_counts * adc_reference_V / PAMKIT_ADC_FULL_SCALE; }
  /// Gauge pressure [kPa] for the transducer's output voltage.
  double pressure_kPa(double volts) const { return pressure_offset_kPa + pressure_kPa_per_V * volts; }
  /// Temperature [degC] for the TMP36's output voltage.
  double temperature_C(double volts) const { return (volts - tmp36_offset_V) / tmp36_V_per_C; }
};

/// Least-squares line through the pressure calibration points.
struct PressureFit {
  double kPa_per_V = 0;         ///< slope [kPa/V]
  double offset_kPa = 0;        ///< gauge pressure at 0 V [kPa]
  double max_residual_kPa = 0;  ///< largest |fit - applied| over the points [kPa]
};

/// Fits gauge pressure = offset + slope * V to the calibration points (appendix B: applied 0, 10,
/// ... 80 psi, voltage read at each).
/// \param applied_psi gauge pressures applied [psi]
/// \param measured_V  voltages read at those pressures [V], same length
/// \throws InvalidInput if fewer than 2 points, lengths differ, a value is not finite, or the
///         voltages do not all differ enough to fix a slope; the message names the point.
PressureFit fit_pressure(const std::vector<double>& applied_psi, const std::vector<double>& measured_V);

}  // namespace pamkit::logger

#include "pamkit/logger/calibration.hxx"
