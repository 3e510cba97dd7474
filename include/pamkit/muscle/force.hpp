#pragma once
/// \file
/// The muscle's axial force, two ways:
///  - `muscle_forces`: the force the simulator uses, from virtual work on the geometry of
///    eqs. 3.1.1-3.1.3 (gas) and on the bladder's strain energy (eqs. 3.1.12-3.1.13), plus
///    friction. It is consistent with the gas equation by construction, so energy balances.
///  - `newtonian_fiber_tensions`: the thesis's fiber-tension formulation (eqs. 3.1.4-3.1.8).
///
/// Sign convention: force > 0 is tension (the muscle pulls its ends together); elongation
/// and its rate are > 0 when the muscle is stretched.

#include <algorithm>
#include <cmath>

#include "pamkit/muscle/bladder.hpp"
#include "pamkit/muscle/friction.hpp"
#include "pamkit/muscle/geometry.hpp"

namespace pamkit {

/// The parts of the muscle force [N].
struct MuscleForces {
  double pressure;  ///< gas and atmosphere: -p dV_gas/dL + p_atm dV_total/dL
  double bladder;   ///< bladder strain energy: V_rubber (sigma_l deps_l/dL + sigma_h deps_h/dL)
  double friction;  ///< eqs. 3.1.19-3.1.24, > 0 while stretching
  double total;     ///< the sum: what a load cell in series reads
};

/// Rubber volume of the bladder's cylindrical part in the deflated build [m^3]; the stress laws
/// are engineering stresses, so they act on this reference volume.
inline double bladder_reference_volume(const BraidGeometry& geometry) noexcept {
  const MuscleBuild& b = geometry.build();
  return detail::kPi * b.bladder_diameter_m * b.bladder_thickness_m * geometry.deflated_cylinder_length();
}

/// Axial force of the muscle.
/// \param absolute_pressure_Pa gas pressure (absolute)
/// \param atmospheric_pressure_Pa ambient pressure (absolute)
/// \param velocity_m_per_s dL/dt, for friction
inline MuscleForces muscle_forces(const BraidGeometry& geometry, const MuscleShape& shape, const BladderLaw& law,
                                  const FrictionParams& friction, double absolute_pressure_Pa,
                                  double atmospheric_pressure_Pa, double velocity_m_per_s) noexcept {
  MuscleForces f{};
  // Virtual work: the gas does work p dV_gas, the atmosphere p_atm dV_total on the outside.
  f.pressure = -absolute_pressure_Pa * shape.d_gas_volume + atmospheric_pressure_Pa * shape.d_total_volume;
  const BladderState b = bladder_state(geometry, shape, law);
  f.bladder = bladder_reference_volume(geometry) *
              (b.longitudinal_stress * b.d_longitudinal_strain + b.hoop_stress * b.d_hoop_strain);
  const double contact_pressure = std::max(absolute_pressure_Pa - atmospheric_pressure_Pa, 0.0);
  f.friction = friction_force(friction, geometry, contact_pressure, velocity_m_per_s);
  f.total = f.pressure + f.bladder + f.friction;
  return f;
}

/// The tension of the braid's fibers together, N T [N]: the force conjugate to their length b
/// over the cylinder. By virtual work at fixed muscle length, with the gas at gauge pressure
/// `gauge_Pa` and the bladder's strain energy E_b,
///     N T = p dV/db - dE_b/db = p dV/db - V_rubber (sigma_l deps_l/db + sigma_h deps_h/db),
/// `viscous` adding the bladder's Maxwell-branch stresses to the elastic ones. It is the hoop
/// stress's pull (a free-inflated muscle, which carries no axial force, tensions its fibers);
/// for a flat-ended braid without bladder it is the hoop balance p Lm b / (2 pi n^2). Negative
/// where the bladder pushes the braid shorter than the gas pulls it.
/// \param fiber the shape's derivatives in the fiber length (BraidGeometry::fiber_length_derivatives)
inline double total_fiber_tension(const BraidGeometry& geometry, const MuscleShape& shape,
                                  const FiberLengthDerivatives& fiber, const BladderLaw& law, double gauge_Pa,
                                  const BiaxialStress& viscous = {0.0, 0.0}) noexcept {
  const BladderState b = bladder_state(geometry, shape, law);
  const double d_longitudinal_strain = fiber.d_cylinder_length / geometry.deflated_cylinder_length();
  const double d_hoop_strain = fiber.d_diameter / geometry.build().bladder_diameter_m;
  return gauge_Pa * fiber.d_gas_volume -
         bladder_reference_volume(geometry) * ((b.longitudinal_stress + viscous.longitudinal) * d_longitudinal_strain +
                                               (b.hoop_stress + viscous.hoop) * d_hoop_strain);
}

/// The slopes of `total_fiber_tension` at fixed gas pressure and viscous stresses [N/m].
struct FiberTensionSlopes {
  double d_fiber;   ///< d(N T)/db at fixed muscle length
  double d_length;  ///< d(N T)/dL at fixed fiber length
};

/// `total_fiber_tension`'s slopes, from the shape's second derivatives in the fiber length
/// (`fiber`) and the bladder law's tangent moduli.
inline FiberTensionSlopes total_fiber_tension_slopes(const BraidGeometry& geometry, const MuscleShape& shape,
                                                     const FiberLengthDerivatives& fiber, const BladderLaw& law,
                                                     double gauge_Pa, const BiaxialStress& viscous = {0.0, 0.0}) {
  const BladderState b = bladder_state(geometry, shape, law);
  const BiaxialStress modulus = law.tangent_moduli(b.longitudinal_strain, b.hoop_strain);
  const double lm0 = geometry.deflated_cylinder_length();
  const double db0 = geometry.build().bladder_diameter_m;
  const double longitudinal_stress = b.longitudinal_stress + viscous.longitudinal;
  const double hoop_stress = b.hoop_stress + viscous.hoop;
  const double longitudinal_b = fiber.d_cylinder_length / lm0;  // d eps_l / db
  const double hoop_b = fiber.d_diameter / db0;                 // d eps_h / db
  const double rubber = bladder_reference_volume(geometry);
  FiberTensionSlopes slopes{};
  slopes.d_fiber = gauge_Pa * fiber.d2_gas_volume -
                   rubber * (modulus.longitudinal * longitudinal_b * longitudinal_b +
                             longitudinal_stress * fiber.d2_cylinder_length / lm0 + modulus.hoop * hoop_b * hoop_b +
                             hoop_stress * fiber.d2_diameter / db0);
  slopes.d_length = gauge_Pa * fiber.d_gas_volume_d_length -
                    rubber * (modulus.longitudinal * b.d_longitudinal_strain * longitudinal_b +
                              longitudinal_stress * fiber.d_cylinder_length_d_length / lm0 +
                              modulus.hoop * b.d_hoop_strain * hoop_b + hoop_stress * fiber.d_diameter_d_length / db0);
  return slopes;
}

/// What a braid transmits of the axial force `force_N` of its gas and bladder [N]: a braid of
/// fibers carries tension but cannot push. Held shorter than its free length, a real muscle goes
/// slack (the braid bunches and the load cell reads zero), where the virtual-work force would
/// turn negative. `band_N` > 0 makes the transition C1-smooth over |force| < band_N (a quadratic
/// blend, so the ODE solver and the fits see no kink); band_N = 0 keeps the thesis's braid,
/// which pushes as readily as it pulls.
/// The slack acts on the force only: the gas volume still follows the length the ends impose.
inline double braid_tension(double force_N, double band_N) noexcept {
  if (band_N <= 0.0 || force_N >= band_N) return force_N;
  if (force_N <= -band_N) return 0.0;
  return (force_N + band_N) * (force_N + band_N) / (4.0 * band_N);
}

/// Fiber tensions of the thesis's Newtonian model [N per fiber] and the force they give.
struct FiberTensions {
  double cylinder_hoop;  ///< Th1, eq. 3.1.6: hoop balance of the cylinder
  double cone_hoop;      ///< Th2, eq. 3.1.7: hoop balance of one cone (reported, see below)
  double longitudinal;   ///< Tl, eq. 3.1.8 re-derived: end-cap load per fiber
  double force;          ///< Fm = N (Th1 - Tl) cos(theta), eq. 3.1.4 at the cylinder's end [N]
};

/// The thesis's Newtonian force (eqs. 3.1.4-3.1.8) at gauge pressure `gauge_pressure_Pa`,
/// without friction.
///
/// Eq. 3.1.8 is garbled in the thesis. Re-derived from the axial balance of the free body made
/// of one end cap and its cone, cut where the fibers leave the cylinder: the gas pushes it out
/// with p pi (D/2 - tf - tb)^2 (the projected area of everything the gas touches, cap and cone
/// together), the bladder's longitudinal stress pulls it in with sigma_l pi Dbo tb, and the N
/// fibers pull it in with T cos(theta). Written as in eq. 3.1.4, Fm = N (T - Tl) cos(theta) with
///     Tl = [p pi (D/2 - tf - tb)^2 - sigma_l pi Dbo tb] / (N cos(theta)),
/// which holds the terms the printed equation still shows. At that cut the fibers run at the
/// cylinder's angle theta and the cone's inclination beta does not enter.
///
/// Eq. 3.1.5 adds 2 Th2 to the fiber tension. A frictionless fiber carries one tension along
/// its length, fixed by the cylinder's hoop balance (Th1), so Th2 is reported but not added.
///
/// With flat ends (no cones), thin walls and no bladder this equals -p dV/dL exactly (virtual
/// work, tests/cpp/force.test.cpp). With the cones of eq. 3.1.1 it does not: the cones of
/// fixed slant length constrain the braid in a way that does no work but carries load, and
/// only the virtual-work force (`muscle_forces`) is consistent with the gas volume.
/// Both stress laws are engineering stresses, applied to the deflated cross-sections
/// (pi Dbo tb longitudinally, tb Lm0 per side in the hoop direction).
inline FiberTensions newtonian_fiber_tensions(const BraidGeometry& geometry, const MuscleShape& shape,
                                              const BladderLaw& law, double gauge_pressure_Pa) {
  const MuscleBuild& b = geometry.build();
  const BladderState bl = bladder_state(geometry, shape, law);
  const double n = b.fiber_revolutions;
  const double N = b.fiber_count;
  const double tb = b.bladder_thickness_m;
  const double tf = b.fiber_thickness_m;
  const double D = shape.diameter;
  const double d = b.end_diameter_m;
  const double p = gauge_pressure_Pa;
  const double lm0 = geometry.deflated_cylinder_length();
  FiberTensions t{};
  t.cylinder_hoop = (p * (D - 2.0 * tb - 2.0 * tf) * shape.cylinder_length - 2.0 * bl.hoop_stress * tb * lm0) /
                    (2.0 * n * N * std::sin(shape.braid_angle));
  // Eq. 3.1.7 with the wall thicknesses taken off the mean cone diameter (the printed "+4tb"
  // would add the bladder to the gas's diameter).
  const double lz = b.cone_generator_m;
  t.cone_hoop = lz > 0.0
                    ? (p * (D + d - 4.0 * tb - 4.0 * tf) * std::cos(shape.cone_angle) - 4.0 * bl.hoop_stress * tb) /
                          (4.0 * n * N * std::sin(shape.mean_braid_angle)) * lz
                    : 0.0;
  const double inner_radius = 0.5 * D - tf - tb;
  t.longitudinal = (p * detail::kPi * inner_radius * inner_radius -
                    bl.longitudinal_stress * detail::kPi * b.bladder_diameter_m * tb) /
                   (N * std::cos(shape.braid_angle));
  t.force = N * (t.cylinder_hoop - t.longitudinal) * std::cos(shape.braid_angle);
  return t;
}

}  // namespace pamkit
