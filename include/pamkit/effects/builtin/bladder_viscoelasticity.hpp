#pragma once
/// \file
/// The catalog effect `bladder_viscoelasticity` (docs/effects.md).

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

/// bladder_viscoelasticity: a Maxwell branch beside the bladder's elastic law.
struct BladderViscoelasticityParams {
  static constexpr const char* kName = "bladder_viscoelasticity";
  static constexpr const char* kDescription =
      "rate-dependent bladder stress: a Maxwell branch (modulus = strength x the law's tangent modulus, relaxation "
      "time tau) beside the elastic law of eqs. 3.1.12-13; the thesis's biaxial tests showed the hysteresis "
      "(figure 3.5). Gives it away: force hysteresis that grows with rate while a cycle is slower than tau, "
      "strongest at low pressure, with no matching pressure hysteresis.";
  static constexpr const char* kSignature = "force hysteresis that pressure does not share";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  double time_constant_s = 2.0;  ///< relaxation time of the Maxwell branch [s]
  double strength = 0.5;         ///< branch modulus over the tangent modulus [1]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("time_constant_s", &BladderViscoelasticityParams::time_constant_s,
          FieldInfo{"s", 1e-4, 1e6, "relaxation time"},
          EffectFieldInfo{{0.5, 20.0},
                          false,
                          {0.2, 100.0,
                           "the thesis's biaxial tests show the hysteresis at cycle times of seconds (figure 3.5); a "
                           "branch relaxing in under 0.2 s is elastic at bench rates, over 100 s a drift"},
                          {FitScale::log, 0.1, 200.0, 2.0}});
    visit("strength", &BladderViscoelasticityParams::strength,
          FieldInfo{"1", 0.0, 100.0, "branch modulus / tangent modulus"},
          EffectFieldInfo{{0.3, 3.0},
                          false,
                          {0.0, 3.0,
                           "a branch stiffer than 3x the elastic tangent modulus means a loss tangent above 1, "
                           "beyond the most damped butyl compounds"},
                          {FitScale::linear, 0.0, 20.0, 0.5},
                          Resolution::any,
                          0.0});  // no branch; its time constant then changes nothing
  }
};
class BladderViscoelasticityEffect : public detail::ParametricEffect<BladderViscoelasticityParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override {
    return detail::dynamic_only(BladderViscoelasticityParams::kName, mode, why_not);
  }
  void apply_to_params(MuscleParams& p) const override {
    p.extensions.viscoelastic_strength = params_.strength;
    p.extensions.viscoelastic_time_constant_s = params_.time_constant_s;
  }
};

}  // namespace pamkit
