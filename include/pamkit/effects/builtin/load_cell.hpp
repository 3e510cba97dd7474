#pragma once
/// \file
/// The catalog effect `load_cell`: the load cell's tare and nonlinearity (docs/effects.md).

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

/// load_cell: the force reading's zero and linearity (the cell's tare, its nonlinearity).
///
/// No gain: a reading 2 % high throughout is absorbed by the calibrated baseline (the inflation
/// pressure moves within its tolerance, the friction and bladder scales with it) to within the
/// noise on two of three of pamkit's nulls (seeds 1-3) and left `unexplained` on the third, so a
/// gain would not be told from the baseline; a share that grows with the force would.
struct LoadCellParams {
  static constexpr const char* kName = "load_cell";
  static constexpr const char* kDescription =
      "zero and linearity error of the load cell: a tare left after zeroing (a cell zeroed with the fixture's "
      "weight on it, or drifted since) and a reading that departs from the force in proportion to its square "
      "(a cell worked far from where it was calibrated). Gives it away: the force is off by a constant at every "
      "rate and in holds, or by a share that grows with the force, while pressure and temperature fit.";
  static constexpr const char* kSignature = "force reads off by a constant or a share growing with the force";
  static constexpr EffectStage kStage = EffectStage::measurement;
  static constexpr const char* kChannel = "force_N";
  static constexpr bool kHasChannel = false;
  double offset_N = 3.0;             ///< reading at zero force [N]
  double nonlinearity_per_kN = 0.0;  ///< relative error of the reading per kN of force [1/kN]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("offset_N", &LoadCellParams::offset_N, FieldInfo{"N", -1e4, 1e4, "load cell reading at zero force"},
          EffectFieldInfo{{2.0, 8.0},
                          true,
                          {-20.0, 20.0,
                           "zero error of a tared cell: 0.02 % of the thesis's 100 kN Instron cell, the zero "
                           "return a strain-gauge cell's datasheet states; a fixture weighed in is a few N"},
                          {FitScale::linear, -50.0, 50.0, 0.0},
                          Resolution::any,
                          0.0});
    visit("nonlinearity_per_kN", &LoadCellParams::nonlinearity_per_kN,
          FieldInfo{"1/kN", -10.0, 10.0, "relative error of the force reading per kN"},
          EffectFieldInfo{{0.05, 0.15},
                          true,
                          {-0.2, 0.2,
                           "ISO 7500-1 class 3: at most 3 % relative error of indication; 0.2/kN gives 6 % at "
                           "300 N, twice that, for a cell used below its verified range"},
                          {FitScale::linear, -0.5, 0.5, 0.0},
                          Resolution::any,
                          0.0});
  }
};
class LoadCellEffect : public detail::ParametricEffect<LoadCellParams> {
 public:
  bool reads_samples_alone() const override { return true; }
  /// reading = offset + F (1 + c F), c per newton.
  void apply_to_measurement(Measurement& m) const override {
    for (double& f : m.force_N) f = params_.offset_N + f * (1.0 + params_.nonlinearity_per_kN * 1e-3 * f);
  }
};

}  // namespace pamkit
