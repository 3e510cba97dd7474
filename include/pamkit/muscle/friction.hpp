#pragma once
/// \file
/// Fiber-fiber and fiber-bladder friction (thesis 3.1.5, eqs. 3.1.19-3.1.24, after Doumit),
/// with the Coulomb law smoothed by tanh (eqs. 3.1.20-3.1.21).

#include <cmath>

#include "pamkit/fields.hpp"
#include "pamkit/muscle/geometry.hpp"

namespace pamkit {

/// Friction parameters. Coefficients from table C.4; the fiber width and contact length are
/// not printed in the thesis and default to the fiber thickness (round fibers crossing).
struct FrictionParams {
  static constexpr const char* kName = "FrictionParams";

  double fiber_fiber_coefficient = 0.2;    ///< mu_d between crossing fibers [1] (Ufd, table C.4)
  double fiber_bladder_coefficient = 0.2;  ///< mu_fb between fibers and bladder [1] (Ub, table C.4)
  double sharpness_s_per_m = 1.0;          ///< Kf in tanh(Kf v) [s/m] (eq. 3.1.21; the thesis used 1)
  double fiber_width_m = 0.254e-3;         ///< fiber width w [m] (eq. 3.1.23; assumed = tf)
  double contact_length_m = 0.254e-3;      ///< z, fiber length in one crossing contact [m] (eq. 3.1.24; assumed = w)

  // With Kf = 1 s/m, tanh(Kf v) = 0.0025 at the bench's 2.5 mm/s: the thesis's friction was
  // almost linear viscous and about 400x below its Coulomb level. Kf is a parameter so a
  // calibration can find the real sharpness.

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("fiber_fiber_coefficient", &FrictionParams::fiber_fiber_coefficient,
          FieldInfo{"1", 0.0, 5.0, "fiber-fiber friction coefficient"});
    visit("fiber_bladder_coefficient", &FrictionParams::fiber_bladder_coefficient,
          FieldInfo{"1", 0.0, 5.0, "fiber-bladder friction coefficient"});
    visit("sharpness_s_per_m", &FrictionParams::sharpness_s_per_m, FieldInfo{"s/m", 0.0, 1e7, "Kf of tanh(Kf v)"});
    visit("fiber_width_m", &FrictionParams::fiber_width_m, FieldInfo{"m", 0.0, 0.01, "fiber width w"});
    visit("contact_length_m", &FrictionParams::contact_length_m,
          FieldInfo{"m", 0.0, 0.01, "fiber length z in one crossing"});
  }
  void validate() const { validate_fields(*this); }
};

/// Friction force [N] at gauge pressure `gauge_pressure_Pa` and elongation rate
/// `velocity_m_per_s` (positive when stretching); positive when it adds to the tension.
/// Sum of fiber-fiber friction, q crossings (eq. 3.1.22) each 2 P A_ff mu_d (eqs. 3.1.19-3.1.20,
/// 3.1.24), and fiber-bladder friction 2 P mu_fb w (Ly N - z q / 2) (eq. 3.1.23), times
/// tanh(Kf v) (eq. 3.1.21).
inline double friction_force(const FrictionParams& p, const BraidGeometry& geometry, double gauge_pressure_Pa,
                             double velocity_m_per_s) noexcept {
  const MuscleBuild& b = geometry.build();
  const double fibers = b.fiber_count;
  const double crossings = 2.0 * b.fiber_revolutions * (0.5 * fibers) * (0.5 * fibers) - 0.5 * fibers;
  const double contact_area = p.fiber_width_m * p.contact_length_m;
  const double fiber_fiber = crossings * 2.0 * gauge_pressure_Pa * contact_area * p.fiber_fiber_coefficient;
  const double bladder_contact = geometry.fiber_length() * fibers - 0.5 * p.contact_length_m * crossings;
  const double fiber_bladder =
      2.0 * gauge_pressure_Pa * p.fiber_bladder_coefficient * p.fiber_width_m * bladder_contact;
  return (fiber_fiber + fiber_bladder) * std::tanh(p.sharpness_s_per_m * velocity_m_per_s);
}

}  // namespace pamkit
