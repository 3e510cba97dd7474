#pragma once
/// \file
/// The catalog effect `braid_slack` (docs/effects.md).

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

/// braid_slack: the braid carries tension but cannot push.
struct BraidSlackParams {
  static constexpr const char* kName = "braid_slack";
  static constexpr const char* kDescription =
      "a braid of fibers that cannot push: held shorter than its free length at the pressure, the muscle goes "
      "slack and carries nothing, where the thesis's braid would push. Gives it away: the measured force stays "
      "at zero where the model's turns negative (short lengths, low pressures of an isometric map; contraction "
      "below the free length).";
  static constexpr const char* kSignature = "force stays at zero where the model pushes";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  double band_N = 1.0;  ///< width of the smooth transition to slack [N]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("band_N", &BraidSlackParams::band_N, FieldInfo{"N", 1e-3, 1e4, "width of the smooth slack transition"},
          EffectFieldInfo{{0.5, 5.0},
                          false,
                          {1e-3, 1e4,
                           "a smoothing width, not a property of the braid: the data cannot tell one width from "
                           "another, so a diagnosis holds it at 1 N"},
                          {FitScale::linear, 1.0, 1.0, 1.0}});
    // No neutral value: narrower bands tend to max(F, 0), the slack braid itself. A band of 0
    // (ModelExtensions::slack_band_N's "the braid can push") is not their limit, so not allowed.
    // The plausible range is the allowed one: no width is more plausible than another.
  }
};
class BraidSlackEffect : public detail::ParametricEffect<BraidSlackParams> {
 public:
  /// A sealed test stretched from its free length keeps the braid taut, and where it would not
  /// (a sealed muscle pushed below its free length) the gas volume should follow the free
  /// length, which the slack force alone does not model. The simulator still honours
  /// ModelExtensions::slack_band_N in sealed runs for those who set it.
  bool acts_in(GasMode mode, std::string* why_not) const override {
    if (mode == GasMode::supplied) return true;
    if (why_not) {
      *why_not =
          "braid_slack acts in supplied tests and static tables; a sealed muscle stretched from its free length "
          "keeps its braid taut";
    }
    return false;
  }
  void apply_to_params(MuscleParams& p) const override { p.extensions.slack_band_N = params_.band_N; }
};

}  // namespace pamkit
