#pragma once
/// \file
/// The catalog effect `time_skew` (docs/effects.md).

#include <vector>

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

/// time_skew: a channel's clock runs behind (or ahead of) the tensile machine's.
struct TimeSkewParams {
  static constexpr const char* kName = "time_skew";
  static constexpr const char* kDescription =
      "constant time offset between channels logged by different instruments (the Arduino's pressure and "
      "temperature against the tensile machine's force), left after a synchronisation by hand. Gives it away: "
      "the cross-correlation of that channel's residual with the prediction's rate peaks away from zero lag.";
  static constexpr const char* kSignature = "{channel} is shifted in time against the machine's channels";
  static constexpr EffectStage kStage = EffectStage::measurement;
  static constexpr bool kHasChannel = true;
  std::string channel = "gauge_pressure_Pa";
  double offset_s = 1.0;  ///< the channel reads at t what happened at t - offset [s]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("offset_s", &TimeSkewParams::offset_s, FieldInfo{"s", -600.0, 600.0, "time offset of the channel"},
          EffectFieldInfo{{0.3, 3.0},
                          true,
                          {-5.0, 5.0,
                           "two instruments started by hand and aligned by eye or by cross-correlation "
                           "(pamkit align): seconds at most"},
                          {FitScale::linear, -6.0, 6.0, 0.0},
                          Resolution::sample_interval,
                          0.0});
  }
};
class TimeSkewEffect : public detail::ParametricEffect<TimeSkewParams> {
 public:
  void apply_to_measurement(Measurement& m) const override {
    if (params_.offset_s == 0.0) return;
    std::vector<double>& x = m.channel(params_.channel);
    const std::vector<double> truth = x;
    const std::vector<double>& t = m.time_s;
    // The times read, t - offset, rise with t: the first sample after each is found by walking on
    // from the last one's (upper_bound's answer, in one pass over the record instead of a search
    // per sample: a diagnosis reads a skew some hundred times per fit).
    std::size_t j = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      const double when = t[k] - params_.offset_s;  // linear interpolation, held at the ends
      while (j < t.size() && t[j] <= when) ++j;
      if (j == 0) {
        x[k] = truth.front();
      } else if (j == t.size()) {
        x[k] = truth.back();
      } else {
        const double f = (when - t[j - 1]) / (t[j] - t[j - 1]);
        x[k] = truth[j - 1] + f * (truth[j] - truth[j - 1]);
      }
    }
  }
};

}  // namespace pamkit
