#pragma once
/// \file
/// The catalog effect `fiber_compliance` (docs/effects.md).

#include "pamkit/effects/parametric.hpp"

namespace pamkit {

/// fiber_compliance: the braid's fibers stretch under their tension, which the gas's hoop stress
/// sets (MuscleModel's fiber balance, sim/model.hpp).
struct FiberComplianceParams {
  static constexpr const char* kName = "fiber_compliance";
  static constexpr const char* kDescription =
      "braid fibers that stretch under their tension (axial stiffness EA of one fiber) to b (1 + T / EA); T is "
      "the force conjugate to their length, N T = p dV/db - dE_bladder/db, the hoop stress's pull, which tensions "
      "them even where the muscle pulls nothing. Gives it away: the muscle widens as the pressure rises, so a "
      "stretch compresses the gas less: force and pressure fall below the baseline, the more so the higher the "
      "pressure.";
  static constexpr const char* kSignature = "force softens at high stretch";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  double stiffness_N = 300.0;  ///< axial stiffness EA of one fiber [N]; inf: inextensible
  template <class V>
  static void for_each_field(V&& visit) {
    visit("stiffness_N", &FiberComplianceParams::stiffness_N,
          FieldInfo{"N", 1.0, detail::kInfinity, "fiber axial stiffness EA (inf: rigid)"},
          EffectFieldInfo{{100.0, 600.0},
                          false,
                          {50.0, detail::kInfinity,
                           "a braid strand of 0.1-0.5 mm^2 polyester or nylon (E = 2-5 GPa) has EA = 200-2500 N; "
                           "the hoop stress of 200-400 kPa pulls each of PAM 2's fibers with 1-3 N, so below 50 N "
                           "the fibers would stretch by several per cent"},
                          {FitScale::reciprocal, 25.0, detail::kInfinity, 300.0},
                          Resolution::any,
                          detail::kInfinity});  // inextensible
  }
};
class FiberComplianceEffect : public detail::ParametricEffect<FiberComplianceParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override {
    return detail::dynamic_only(FiberComplianceParams::kName, mode, why_not);
  }
  void apply_to_params(MuscleParams& p) const override {
    p.extensions.fiber_compliance_per_N = 1.0 / params_.stiffness_N;
  }
};

}  // namespace pamkit
