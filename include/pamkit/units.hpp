#pragma once
/// \file
/// Units and conversions used where a quantity crosses a boundary in other units than SI
/// (a CSV column in kPa, a transducer calibrated in psi, a sensor that reads degC). Declared
/// once here and exported to Python as `pamkit.units`, so no other file restates a factor.
/// Header-only, with no dependency: the firmware-free controller target can use it too.

namespace pamkit::units {

/// Pascals in one kilopascal.
inline constexpr double kPascalPerKilopascal = 1e3;
/// Kilopascals in one psi: 1 psi = 6894.757293168 Pa (NIST SP 811; appendix G.2 rounds it to 6895 Pa).
inline constexpr double kKilopascalPerPsi = 6.894757293168361;
/// Kelvin at 0 degC.
inline constexpr double kKelvinAtZeroCelsius = 273.15;
/// Millimetres in one metre.
inline constexpr double kMillimetrePerMetre = 1e3;

/// Gauge pressure [kPa] to [Pa].
inline constexpr double pascal_from_kilopascal(double kilopascal) { return kilopascal * kPascalPerKilopascal; }
/// Pressure [Pa] to [kPa].
inline constexpr double kilopascal_from_pascal(double pascal) { return pascal / kPascalPerKilopascal; }
/// Temperature [degC] to [K].
inline constexpr double kelvin_from_celsius(double celsius) { return celsius + kKelvinAtZeroCelsius; }
/// Temperature [K] to [degC].
inline constexpr double celsius_from_kelvin(double kelvin) { return kelvin - kKelvinAtZeroCelsius; }

}  // namespace pamkit::units
