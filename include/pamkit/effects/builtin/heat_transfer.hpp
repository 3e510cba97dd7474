#pragma once
/// \file
/// The catalog effect `heat_transfer` (docs/effects.md).

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

/// heat_transfer: the gas exchanges heat with the wall at a finite rate (time constant tau)
/// instead of following a fixed polytropic exponent. tau = 0 is instantaneous exchange, the
/// isothermal baseline.
struct HeatTransferParams {
  static constexpr const char* kName = "heat_transfer";
  static constexpr const char* kDescription =
      "finite-rate heat exchange between gas and wall, in place of a fixed polytropic exponent. Gives it away: "
      "pressure hysteresis that grows with rate while a cycle is slower than tau (and shrinks toward adiabatic "
      "beyond), pressure that relaxes during holds, temperature swings far below the polytropic ones.";
  static constexpr const char* kSignature = "pressure loops open up with rate and the gas exchanges heat with the wall";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  /// gas-wall exchange time constant [s]; the gas model's own default (table 3.6)
  double time_constant_s = GasParams{}.heat_transfer_time_constant_s;
  template <class V>
  static void for_each_field(V&& visit) {
    visit("time_constant_s", &HeatTransferParams::time_constant_s,
          FieldInfo{"s", 0.0, 1e9, "gas-wall heat exchange time constant"},
          EffectFieldInfo{{0.5, 10.0},
                          false,
                          {0.05, 30.0,
                           "0.38 s reproduces table 3.6 on the thesis muscle (forced flow into the cones); natural "
                           "convection in a 20-30 mm muscle gives 0.8-3.8 s (docs/table_3_6.md); a factor 8 below "
                           "for small muscles and above for thick, slow walls"},
                          {FitScale::log, 0.02, 200.0, 2.0},
                          Resolution::any,
                          0.0});  // instantaneous exchange: the default, isothermal gas
  }
};
class HeatTransferEffect : public detail::ParametricEffect<HeatTransferParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override {
    return detail::sealed_only(HeatTransferParams::kName, mode, why_not);
  }
  void apply_to_params(MuscleParams& p) const override {
    p.gas.process = GasProcess::heat_transfer;
    p.gas.heat_transfer_time_constant_s = params_.time_constant_s;
  }
};

}  // namespace pamkit
