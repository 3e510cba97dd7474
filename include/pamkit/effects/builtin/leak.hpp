#pragma once
/// \file
/// The catalog effect `leak` (docs/effects.md).

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

/// leak: gas escapes through an orifice; the gauge pressure decays with tau at fixed volume.
struct LeakParams {
  static constexpr const char* kName = "leak";
  static constexpr const char* kDescription =
      "gas escaping through an orifice (a seal, the sensor's wires): the gauge pressure decays with a time constant. "
      "Gives it away: pressure and force peaks drift down cycle after cycle.";
  static constexpr const char* kSignature = "peaks drift down cycle after cycle";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  double time_constant_s = 1000.0;  ///< decay time of the gauge pressure at fixed volume [s]; inf: sealed
  template <class V>
  static void for_each_field(V&& visit) {
    visit("time_constant_s", &LeakParams::time_constant_s,
          FieldInfo{"s", 1e-3, detail::kInfinity, "leak time constant (inf: none)"},
          EffectFieldInfo{{100.0, 3000.0},
                          false,
                          {20.0, detail::kInfinity,
                           "a sealed test runs 5-10 stretch cycles of 2-200 s after one inflation; a muscle that "
                           "loses 63 % of its gauge pressure in under 20 s could not be tested sealed"},
                          {FitScale::reciprocal, 5.0, detail::kInfinity, 1000.0},
                          Resolution::any,
                          detail::kInfinity});  // sealed
  }
};
class LeakEffect : public detail::ParametricEffect<LeakParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override {
    return detail::sealed_only(LeakParams::kName, mode, why_not);
  }
  void apply_to_params(MuscleParams& p) const override { p.extensions.leak_rate_per_s = 1.0 / params_.time_constant_s; }
};

}  // namespace pamkit
