#pragma once
/// \file
/// The factors between SI and the units people read and write: a CSV column in kPa, bar or degC, a
/// transducer calibrated in psi, a plot in millimetres. Every API of pamkit is SI; these are used
/// only where a file, a calibration or a plot meets a person. Declared once here and exported to
/// Python as `pamkit.units`, so no other file restates a factor. Header-only, with no dependency:
/// the firmware-free controller target can use it too.

namespace pamkit::units {

/// Pascals in one kilopascal.
inline constexpr double kPascalPerKilopascal = 1e3;
/// Kilopascals in one psi: 1 psi = 6894.757293168 Pa (NIST SP 811; appendix G.2 rounds it to 6895 Pa).
inline constexpr double kKilopascalPerPsi = 6.894757293168361;
/// Kilopascals in one bar (1 bar = 1e5 Pa exactly): a regulator's or a datasheet's pressure.
inline constexpr double kKilopascalPerBar = 100.0;
/// Newtons in one kilogram-force: standard gravity, 9.80665 m/s^2 exactly (CGPM 1901), the weight
/// of a kilogram hung on a muscle and a load cell's kgf.
inline constexpr double kNewtonPerKilogramForce = 9.80665;
/// Kelvin at 0 degC.
inline constexpr double kKelvinAtZeroCelsius = 273.15;
/// Millimetres in one metre.
inline constexpr double kMillimetrePerMetre = 1e3;

}  // namespace pamkit::units
