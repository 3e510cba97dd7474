#pragma once
/// \file
/// The catalog effect `pressure_hysteresis` (docs/effects.md).

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

/// pressure_hysteresis: rate-independent friction between bladder and braid as the supplied
/// pressure is raised and lowered.
struct PressureHysteresisParams {
  static constexpr const char* kName = "pressure_hysteresis";
  static constexpr const char* kDescription =
      "rate-independent friction between the bladder and the braid as the supplied pressure is raised and lowered "
      "(a Coulomb friction proportional to the pressure force p pi D^2/4): raising the pressure the muscle shows less "
      "tension than its elastic force, lowering it more. Gives it away: at the same pressure and length the force "
      "on venting lies above the force on pressurising; under a load, the muscle is shorter on venting; the loop "
      "does not shrink with slower steps.";
  static constexpr const char* kSignature = "force on venting above force on pressurising, at any rate";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  double coefficient = 0.1;  ///< friction over the pressure force p pi D^2/4 [1]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("coefficient", &PressureHysteresisParams::coefficient,
          FieldInfo{"1", 0.0, 10.0, "pressurise/vent friction over the pressure force p pi D^2/4"},
          EffectFieldInfo{{0.03, 0.3},
                          false,
                          {0.0, 1.0,
                           "rubber on a polyamide or aramid braid has a friction coefficient of 0.3-1, and only part "
                           "of the pressure force presses the bladder into the braid's crossings: above 1 the "
                           "friction would exceed the whole pressure force"},
                          {FitScale::linear, 0.0, 2.0, 0.05},
                          Resolution::any,
                          0.0});
  }
};
class PressureHysteresisEffect : public detail::ParametricEffect<PressureHysteresisParams> {
 public:
  bool shows_between_branches() const override { return true; }
  /// In a sealed test the pressure follows the stretch, and the thesis's friction (eqs.
  /// 3.1.19-3.1.24) already acts on the braid's velocity.
  bool acts_in(GasMode mode, std::string* why_not) const override {
    if (mode == GasMode::supplied) return true;
    if (why_not) {
      *why_not =
          "pressure_hysteresis acts where a supplied pressure is raised and lowered; in a sealed test the thesis's "
          "friction acts on the braid's velocity";
    }
    return false;
  }
  void apply_to_params(MuscleParams& p) const override { p.extensions.pressure_hysteresis = params_.coefficient; }
};

}  // namespace pamkit
