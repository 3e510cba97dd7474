#pragma once
/// \file
/// The bladder's biaxial stress laws (thesis 3.1.2, eqs. 3.1.12-3.1.13) and its strains,
/// taken from the braid geometry as in table 3.1.

#include <array>
#include <cmath>

#include "pamkit/error.hpp"

#include "pamkit/muscle/geometry.hpp"

namespace pamkit {

/// Engineering (nominal) stresses of the bladder in its two in-plane directions [Pa], or the
/// tangent moduli d sigma / d eps of each direction in its own strain [Pa].
struct BiaxialStress {
  double longitudinal;
  double hoop;
};

/// The bladder's membrane law: engineering stress [Pa] in the longitudinal and hoop directions
/// as functions of the two strains. Two forms:
///  - `polynomial`: each stress a polynomial of the strain in its own direction, the form of the
///    thesis's fits to biaxial tests of butyl rubber (eqs. 3.1.12-3.1.13);
///  - `neo_hookean`: an incompressible neo-Hookean membrane with shear modulus mu, whose
///    thickness follows from the two stretches (lambda_3 = 1 / (lambda_l lambda_h)). Its stresses
///    derive from the strain energy W = mu/2 (lambda_l^2 + lambda_h^2 + lambda_3^2 - 3) per unit
///    deflated volume, so the bladder force of `muscle_forces` is the derivative of a stored
///    energy. A moulded membrane with embedded fibres (a Festo fluidic muscle) is not butyl
///    tube: this is the law with one physical parameter to calibrate on it.
/// `none()` switches the bladder off.
struct BladderLaw {
  enum class Form { polynomial, neo_hookean };

  Form form = Form::polynomial;
  /// Polynomial form: coefficients c0..c6 [Pa] of sigma_l = sum c_k eps_l^k.
  std::array<double, 7> longitudinal_Pa{};
  /// Polynomial form: coefficients c0..c6 [Pa] of sigma_h = sum c_k eps_h^k.
  std::array<double, 7> hoop_Pa{};
  /// Neo-Hookean form: shear modulus mu [Pa] (rubbers: 0.2-3 MPa).
  double shear_modulus_Pa = 0.0;

  /// Eqs. 3.1.12 and 3.1.13 (butyl rubber, sample 5, strain ratio -0.278/0.93), in Pa.
  /// Eq. 3.1.13 as printed lost the operator before 19462 eps^4: it is "+" (with "-" the hoop
  /// stress turns negative near 90 % strain, where the biaxial tests measured it highest).
  static BladderLaw thesis() {
    BladderLaw law;
    law.longitudinal_Pa = {0.0, 0.0, -3700e3, -52700e3, -438900e3, -1553000e3, -2018400e3};
    law.hoop_Pa = {-81e3, 2046e3, -1415e3, -4759e3, 19462e3, -24717e3, 11166e3};
    return law;
  }
  /// An incompressible neo-Hookean membrane of shear modulus `shear_modulus_Pa`.
  /// \throws InvalidParameter if the modulus is negative or not finite.
  static BladderLaw neo_hookean(double shear_modulus_Pa) {
    if (!(shear_modulus_Pa >= 0.0) || !std::isfinite(shear_modulus_Pa)) {
      PAMKIT_THROW(InvalidParameter(
          detail::message("BladderLaw.shear_modulus_Pa = ", shear_modulus_Pa, " Pa must be finite and >= 0")));
    }
    BladderLaw law;
    law.form = Form::neo_hookean;
    law.shear_modulus_Pa = shear_modulus_Pa;
    return law;
  }
  /// No bladder stress at all.
  static BladderLaw none() { return BladderLaw{}; }

  /// Engineering stresses [Pa] at longitudinal strain `eps_l` and hoop strain `eps_h`.
  BiaxialStress stresses(double eps_l, double eps_h) const noexcept {
    if (form == Form::neo_hookean) {
      // dW/d lambda_i with lambda_3 = 1 / (lambda_l lambda_h) eliminated.
      const double ll = 1.0 + eps_l;
      const double lh = 1.0 + eps_h;
      const double thinning = 1.0 / (ll * ll * lh * lh);
      return {shear_modulus_Pa * (ll - thinning / ll), shear_modulus_Pa * (lh - thinning / lh)};
    }
    return {evaluate(longitudinal_Pa, eps_l), evaluate(hoop_Pa, eps_h)};
  }
  /// Tangent moduli d sigma_l / d eps_l and d sigma_h / d eps_h [Pa].
  BiaxialStress tangent_moduli(double eps_l, double eps_h) const {
    if (form == Form::neo_hookean) {
      const double ll = 1.0 + eps_l;
      const double lh = 1.0 + eps_h;
      const double thinning = 1.0 / (ll * ll * lh * lh);
      return {shear_modulus_Pa * (1.0 + 3.0 * thinning / (ll * ll)),
              shear_modulus_Pa * (1.0 + 3.0 * thinning / (lh * lh))};
    }
    return {slope(longitudinal_Pa, eps_l), slope(hoop_Pa, eps_h)};
  }

 private:
  static double evaluate(const std::array<double, 7>& c, double x) noexcept {
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
inline BladderState bladder_state(const BraidGeometry& geometry, const MuscleShape& shape,
                                  const BladderLaw& law) noexcept {
  const double lm0 = geometry.deflated_cylinder_length();
  const double db0 = geometry.build().bladder_diameter_m;
  BladderState b{};
  b.longitudinal_strain = shape.cylinder_length / lm0 - 1.0;
  b.hoop_strain = shape.diameter / db0 - 1.0;
  b.d_longitudinal_strain = shape.d_cylinder_length / lm0;
  b.d_hoop_strain = shape.d_diameter / db0;
  const BiaxialStress stress = law.stresses(b.longitudinal_strain, b.hoop_strain);
  b.longitudinal_stress = stress.longitudinal;
  b.hoop_stress = stress.hoop;
  return b;
}

}  // namespace pamkit
