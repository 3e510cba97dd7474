#pragma once
/// \file
/// The catalog effect `fixture_slack` (docs/effects.md).

#include <algorithm>
#include <vector>

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

/// fixture_slack: play between crosshead and muscle (loose pins).
struct FixtureSlackParams {
  static constexpr const char* kName = "fixture_slack";
  static constexpr const char* kDescription =
      "slack between crosshead and muscle (pins in loose holes): the muscle moves only once the crosshead has "
      "taken up the play, at each reversal. Gives it away: force stays flat at the start of each stretch and "
      "each return; the force-elongation loop is shifted and widened by the slack.";
  static constexpr const char* kSignature = "force stays flat at the start of each stretch";
  static constexpr EffectStage kStage = EffectStage::motion;
  static constexpr bool kHasChannel = false;
  double slack_m = 1e-3;  ///< total play [m]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("slack_m", &FixtureSlackParams::slack_m, FieldInfo{"m", 0.0, 0.05, "play between crosshead and muscle"},
          EffectFieldInfo{{0.5e-3, 3e-3},
                          false,
                          {0.0, 5e-3,
                           "pins in loose holes: two clearance fits of 0.1-1 mm each; 5 mm of play is a visibly "
                           "loose fixture"},
                          {FitScale::linear, 0.0, 0.02, 1e-3},
                          Resolution::travel_per_sample,
                          0.0});
  }
};
class FixtureSlackEffect : public detail::ParametricEffect<FixtureSlackParams> {
 public:
  /// A play (backlash) operator: the muscle stays put until the crosshead pushes it from
  /// either end of a band `slack_m` wide; it starts at the band's upper end.
  std::vector<double> apply_to_elongation(const std::vector<double>&,
                                          const std::vector<double>& crosshead) const override {
    std::vector<double> muscle(crosshead.size());
    double position = crosshead.empty() ? 0.0 : crosshead.front();
    for (std::size_t k = 0; k < crosshead.size(); ++k) {
      position = std::clamp(position, crosshead[k] - params_.slack_m, crosshead[k]);
      muscle[k] = position;
    }
    return muscle;
  }
};

}  // namespace pamkit
