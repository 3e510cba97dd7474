#pragma once
/// \file
/// The bladder's biaxial stress laws (thesis 3.1.2, eqs. 3.1.12-3.1.13) and its strains,
/// taken from the braid geometry as in table 3.1.

#include <array>

#include "pamkit/muscle/geometry.hpp"

namespace pamkit {

/// A biaxial stress law: engineering stress [Pa] in the longitudinal and hoop directions,
/// each a polynomial of the strain in its own direction (the form of eqs. 3.1.12-3.1.13).
/// Replace it by constructing one with other coefficients; `none()` switches the bladder off.
struct BladderLaw {
  /// Coefficients c0..c6 [Pa] of sigma_l = sum c_k eps_l^k.
  std::array<double, 7> longitudinal_Pa{};
  /// Coefficients c0..c6 [Pa] of sigma_h = sum c_k eps_h^k.
  std::array<double, 7> hoop_Pa{};

  /// Eqs. 3.1.12 and 3.1.13 (butyl rubber, sample 5, strain ratio -0.278/0.93), in Pa.
  /// Eq. 3.1.13 as printed lost the operator before 19462 eps^4: it is "+" (with "-" the hoop
  /// stress turns negative near 90 % strain, where the biaxial tests measured it highest).
  static BladderLaw thesis() {
    BladderLaw law;
    law.longitudinal_Pa = {0.0, 0.0, -3700e3, -52700e3, -438900e3, -1553000e3, -2018400e3};
    law.hoop_Pa = {-81e3, 2046e3, -1415e3, -4759e3, 19462e3, -24717e3, 11166e3};
    return law;
  }
  /// No bladder stress at all.
  static BladderLaw none() { return BladderLaw{}; }

  double longitudinal_stress(double strain) const { return evaluate(longitudinal_Pa, strain); }
  double hoop_stress(double strain) const { return evaluate(hoop_Pa, strain); }
  /// Tangent modulus d sigma_l / d eps_l [Pa].
  double longitudinal_modulus(double strain) const { return slope(longitudinal_Pa, strain); }
  /// Tangent modulus d sigma_h / d eps_h [Pa].
  double hoop_modulus(double strain) const { return slope(hoop_Pa, strain); }

 private:
  static double evaluate(const std::array<double, 7>& c, double x) {
    double value = 0.0;
    for (auto k = c.size(); k-- > 0;) value = value * x + c[k];
    return value;
  }
  static double slope(const std::array<double, 7>& c, double x) {
    double value = 0.0;
    for (auto k = c.size(); k-- > 1;) value = value * x + static_cast<double>(k) * c[k];
    return value;
  }
};

/// Bladder strains and stresses at one shape.
struct BladderState {
  double longitudinal_strain;    ///< eps_l = Lm / Lm_deflated - 1 [1]
  double hoop_strain;            ///< eps_h = D / D_bladder,deflated - 1 [1] (as table 3.1)
  double d_longitudinal_strain;  ///< d eps_l / dL [1/m]
  double d_hoop_strain;          ///< d eps_h / dL [1/m]
  double longitudinal_stress;    ///< sigma_l [Pa]
  double hoop_stress;            ///< sigma_h [Pa]
};

/// Strains follow the geometry: the bladder lies against the braid, so its hoop strain is the
/// braid diameter over the deflated bladder diameter, and its length follows the cylinder.
inline BladderState bladder_state(const BraidGeometry& geometry, const MuscleShape& shape, const BladderLaw& law) {
  const double lm0 = geometry.deflated_cylinder_length();
  const double db0 = geometry.build().bladder_diameter_m;
  BladderState b{};
  b.longitudinal_strain = shape.cylinder_length / lm0 - 1.0;
  b.hoop_strain = shape.diameter / db0 - 1.0;
  b.d_longitudinal_strain = shape.d_cylinder_length / lm0;
  b.d_hoop_strain = shape.d_diameter / db0;
  b.longitudinal_stress = law.longitudinal_stress(b.longitudinal_strain);
  b.hoop_stress = law.hoop_stress(b.hoop_strain);
  return b;
}

}  // namespace pamkit
