#pragma once
/// \file
/// The closed mass of air inside the muscle (thesis 3.1.3-3.1.4): ideal gas (eq. 3.1.17),
/// either a polytropic process (eqs. 3.1.14-3.1.18) or an energy balance with heat exchange
/// to the wall at a finite rate, which spans isothermal (fast exchange) to adiabatic (none).
/// Pressures are absolute unless the name says gauge.

#include <cmath>
#include <string>

#include "pamkit/fields.hpp"

namespace pamkit {

/// How the gas exchanges heat with the muscle wall.
enum class GasProcess {
  polytropic,    ///< p V^n = const (eq. 3.1.14); n = 1 isothermal, n = 1.4 adiabatic
  heat_transfer  ///< m cv dT/dt = -p dV/dt + m cv (T_ambient - T) / tau
};

/// Air and its surroundings, and the gas process.
struct GasParams {
  static constexpr const char* kName = "GasParams";

  double gas_constant_J_per_kgK = 287.0;   ///< R, dry air [J/(kg K)] (table C.4)
  double heat_capacity_ratio = 1.4;        ///< gamma = cp / cv of air [1]
  double atmospheric_pressure_Pa = 101e3;  ///< absolute ambient pressure [Pa] (Patm, table C.4)
  double ambient_temperature_K = 296.0;    ///< ambient, and initial gas, temperature [K] (Tatm, table C.4)
  double polytropic_index = 1.0;           ///< n of eq. 3.1.14 [1]; 1.0 fitted the thesis's tests best
  double heat_transfer_time_constant_s =
      0.38;  ///< tau of the gas-wall exchange [s] (heat_transfer only); 0: instantaneous
             ///< (isothermal). 0.38 s reproduces table 3.6 (docs/table_3_6.md)
  GasProcess process = GasProcess::polytropic;  ///< which law governs the gas temperature

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("gas_constant_J_per_kgK", &GasParams::gas_constant_J_per_kgK,
          FieldInfo{"J/(kg K)", 1.0, 1e5, "specific gas constant R"});
    visit("heat_capacity_ratio", &GasParams::heat_capacity_ratio, FieldInfo{"1", 1.0001, 1.7, "cp / cv"});
    visit("atmospheric_pressure_Pa", &GasParams::atmospheric_pressure_Pa,
          FieldInfo{"Pa", 1e3, 1e6, "absolute ambient pressure"});
    visit("ambient_temperature_K", &GasParams::ambient_temperature_K,
          FieldInfo{"K", 150.0, 500.0, "ambient and initial gas temperature"});
    visit("polytropic_index", &GasParams::polytropic_index, FieldInfo{"1", 1.0, 1.7, "polytropic exponent n"});
    visit("heat_transfer_time_constant_s", &GasParams::heat_transfer_time_constant_s,
          FieldInfo{"s", 0.0, 1e9, "gas-wall heat exchange time constant (0: isothermal)"});
  }
  void validate() const { validate_fields(*this); }

  /// cv = R / (gamma - 1) [J/(kg K)].
  double specific_heat_cv() const { return gas_constant_J_per_kgK / (heat_capacity_ratio - 1.0); }
};

/// Eq. 3.1.16: absolute pressure after a polytropic change from (p0, V0) to V.
inline double polytropic_pressure(double p0_abs_Pa, double v0_m3, double v_m3, double n) {
  return p0_abs_Pa * std::pow(v0_m3 / v_m3, n);
}

/// Eq. 3.1.18: temperature after a polytropic change from (T0, V0) to V.
inline double polytropic_temperature(double t0_K, double v0_m3, double v_m3, double n) {
  return t0_K * std::pow(v0_m3 / v_m3, n - 1.0);
}

inline const char* to_string(GasProcess process) {
  return process == GasProcess::polytropic ? "polytropic" : "heat_transfer";
}

}  // namespace pamkit
