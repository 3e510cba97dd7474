#pragma once
/// \file
/// The catalog effect `dead_volume` (docs/effects.md).

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

/// dead_volume: gas outside the muscle (hose, transducer) whose volume does not change.
struct DeadVolumeParams {
  static constexpr const char* kName = "dead_volume";
  static constexpr const char* kDescription =
      "gas volume outside the muscle that does not change with stretch (hose and transducer: about 5 % in the "
      "thesis, appendix B). Gives it away: the pressure swing is scaled down evenly, at every rate.";
  static constexpr const char* kSignature = "the pressure swings less than the muscle's volume change implies, evenly";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  double volume_fraction = 0.05;  ///< dead volume over the muscle's initial gas volume [1]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("volume_fraction", &DeadVolumeParams::volume_fraction,
          FieldInfo{"1", 0.0, 10.0, "dead volume / initial gas volume"},
          EffectFieldInfo{{0.03, 0.3},
                          false,
                          {0.0, 0.6,
                           "hose and transducer: 5 % in the thesis (appendix B); a metre of 4 mm hose is 9 % of the "
                           "thesis muscle's 140 cm^3; more than 60 % needs a reservoir the test would declare"},
                          {FitScale::linear, 0.0, 1.0, 0.1},
                          Resolution::any,
                          0.0});
  }
};
class DeadVolumeEffect : public detail::ParametricEffect<DeadVolumeParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override {
    return detail::sealed_only(DeadVolumeParams::kName, mode, why_not);
  }
  void apply_to_params(MuscleParams& p) const override { p.extensions.dead_volume_fraction = params_.volume_fraction; }
};

}  // namespace pamkit
