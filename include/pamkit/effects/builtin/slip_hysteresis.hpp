#pragma once
/// \file
/// The catalog effect `slip_hysteresis` (docs/effects.md).

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

/// slip_hysteresis: friction with memory inside the membrane, as Maxwell-slip elements that
/// follow the braid's motion (muscle/slip.hpp).
struct SlipHysteresisParams {
  static constexpr const char* kName = "slip_hysteresis";
  static constexpr const char* kDescription =
      "friction with memory between the fibres and the rubber they move in: Maxwell-slip elements of one stiffness "
      "whose break-away displacements spread evenly up to the slip distance (Iwan's model) that follow the braid's "
      "length, each springing back until it slips (Vo-Minh et al. 2011 found this model on pneumatic muscles); from "
      "rest the friction rises as f (2 x / d - (x / d)^2) to its slip force f at the slip distance d. "
      "Rate-independent, so a loop survives "
      "settled steps, and what the elements hold stays when the motion stops: a muscle that contracted to a held "
      "length pulls less than its elastic force at every pressure, one that lengthened to it more, vented or not. "
      "Gives it away: an isometric map's force lies a constant below the elastic one at every length the muscle "
      "contracted to, and not at its rest length; isotonic loops that settled steps leave open; force left at zero "
      "pressure after a sweep.";
  static constexpr const char* kSignature = "a constant force offset wherever the braid moved; loops at rest";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  double slip_force_N = 50.0;     ///< what the elements hold when all slip [N]
  double slip_distance_m = 0.01;  ///< the break-away displacements spread over (0, this] [m]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("slip_force_N", &SlipHysteresisParams::slip_force_N,
          FieldInfo{"N", 0.0, 1e5, "the elements' slip force together"},
          EffectFieldInfo{{10.0, 200.0},
                          false,
                          {0.0, 1000.0,
                           "the published DMSP-10 and DMSP-20 maps hold 190 and 300 N, a third and a fifth of their "
                           "force at 6 bar (data/experiments/festo); 1 kN is a sixth of the largest Festo muscle's "
                           "6 kN"},
                          {FitScale::linear, 0.0, 2000.0, 50.0},
                          Resolution::any,
                          0.0});  // no elements; their distance then changes nothing
    visit("slip_distance_m", &SlipHysteresisParams::slip_distance_m,
          FieldInfo{"m", 1e-6, 1.0, "the break-away displacements spread over (0, this]"},
          EffectFieldInfo{{0.002, 0.02},
                          false,
                          {5e-4, 0.05,
                           "the maps' offsets are full within 10-25 mm of contraction; below 0.5 mm the elements are "
                           "a Coulomb friction (pressure_hysteresis), above 50 mm longer than the quarter contraction "
                           "of a 200 mm muscle"},
                          {FitScale::log, 1e-4, 0.1, 0.01}});
  }
};
class SlipHysteresisEffect : public detail::ParametricEffect<SlipHysteresisParams> {
 public:
  /// A sealed test is the thesis's cyclic stretch, whose friction is eqs. 3.1.19-3.1.24 on the
  /// braid's velocity; the elements' states are followed where a table's rows or a supplied
  /// test's samples give the path.
  bool acts_in(GasMode mode, std::string* why_not) const override {
    if (mode == GasMode::supplied) return true;
    if (why_not) {
      *why_not =
          "slip_hysteresis acts in supplied tests and static tables; in a sealed test the thesis's friction acts on "
          "the braid's velocity";
    }
    return false;
  }
  void apply_to_params(MuscleParams& p) const override {
    p.extensions.slip_force_N = params_.slip_force_N;
    p.extensions.slip_distance_m = params_.slip_distance_m;
  }
};

}  // namespace pamkit
