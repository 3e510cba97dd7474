// The muscle force two ways: virtual work on the gas volume (what the simulator uses) and the
// thesis's Newtonian fiber tensions (eqs. 3.1.4-3.1.8), checked against each other and against
// -p dV/dL.

#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "pamkit/muscle/force.hpp"

namespace {

using namespace pamkit;

constexpr double kPi = 3.14159265358979323846;
constexpr double kAtmosphere = 101e3;  // Patm, table C.4
const FrictionParams kNoFriction{0.0, 0.0, 0.0, 0.0, 0.0};

// Thin walls: no bladder or fiber thickness, so the gas fills the braid (V_gas = V_total).
MuscleBuild thin_walls(double cone_generator_m) {
  MuscleBuild b;
  b.bladder_thickness_m = 0.0;
  b.fiber_thickness_m = 0.0;
  b.cone_generator_m = cone_generator_m;
  return b;
}

std::vector<double> working_lengths() { return {0.15, 0.16, 0.17, 0.18, 0.19, 0.20, 0.21, 0.22}; }

// -dV_total/dL by central differences (h = 1e-6 m; error ~1e-10 of pi D^2/4, see geometry.test.cpp).
double minus_dV_dL(const BraidGeometry& geometry, double L) {
  const double h = 1e-6;
  return -(geometry.shape(L + h).total_volume - geometry.shape(L - h).total_volume) / (2.0 * h);
}

}  // namespace

TEST_CASE("Virtual work: the pressure force is -p dV/dL, cones included", "[force][physics]") {
  // Frictionless, inextensible braid and no bladder: the only work is the gauge pressure's on
  // the volume, so F = -p_gauge dV/dL. Tolerance 1e-7 of p pi D^2/4, as the derivative check.
  const double gauge = 200e3;
  for (double cone : {0.0095, 0.0}) {
    const BraidGeometry geometry(thin_walls(cone));
    for (double L : working_lengths()) {
      INFO("cone_generator_m = " << cone << ", L = " << L);
      const MuscleShape s = geometry.shape(L);
      const MuscleForces f =
          muscle_forces(geometry, s, BladderLaw::none(), kNoFriction, kAtmosphere + gauge, kAtmosphere, 0.0);
      const double expected = gauge * minus_dV_dL(geometry, L);
      CHECK(std::abs(f.pressure - expected) <= 1e-7 * gauge * 0.25 * kPi * s.diameter * s.diameter);
      CHECK(f.bladder == 0.0);
      CHECK(f.friction == 0.0);
      CHECK(f.total == f.pressure);
    }
  }
}

TEST_CASE("Newtonian fiber tensions with flat ends equal -p dV/dL and the closed form", "[force][physics]") {
  // Flat ends, thin walls, no bladder: eqs. 3.1.4-3.1.8 reduce to
  //   F = p Lym^2 (3 cos^2 theta - 1) / (4 pi n^2),
  // which is -p dV/dL for V = pi D^2 Lm / 4 with eqs. 3.1.9-3.1.10 (the classic McKibben law).
  const double gauge = 150e3;
  const BraidGeometry geometry(thin_walls(0.0));
  const double n = geometry.build().fiber_revolutions;
  const double lym = geometry.fiber_length();
  for (double L : working_lengths()) {
    INFO("L = " << L);
    const MuscleShape s = geometry.shape(L);
    const FiberTensions t = newtonian_fiber_tensions(geometry, s, BladderLaw::none(), gauge);
    const double c = std::cos(s.braid_angle);
    const double closed_form = gauge * lym * lym * (3.0 * c * c - 1.0) / (4.0 * kPi * n * n);
    const double scale = gauge * 0.25 * kPi * s.diameter * s.diameter;
    CHECK(std::abs(t.force - closed_form) <= 1e-12 * scale);
    CHECK(std::abs(t.force - gauge * minus_dV_dL(geometry, L)) <= 1e-7 * scale);
    CHECK(t.cone_hoop == 0.0);  // no cones, no eq. 3.1.7
  }
}

TEST_CASE("Newtonian and virtual-work forces differ only by the wall's work, with flat ends and the thesis bladder",
          "[force][physics]") {
  // One algorithm against another. The bladder is on (eqs. 3.1.12-3.1.13, table C.4's 0.254 mm)
  // and both formulations apply the engineering stresses to the deflated cross-sections
  // (pi Dbo tb lengthwise, tb Lm0 per side around), so the bladder terms agree term by term.
  // Fiber thickness is 0: the Newtonian balance takes tf off the gas's radius.
  //
  // The walls differ. The Newtonian balance takes the gas's radius as D/2 - tb at every length:
  // a wall of constant thickness, whose rubber volume is eq. 3.1.3's V_w(L) = pi L (D tb - tb^2).
  // pamkit's wall conserves its volume (rubber is incompressible), so the gas does work on the
  // whole braid volume: F_newton = F_vw + p dV_w/dL exactly, with dV_w/dL from eq. 3.1.3 in
  // closed form. And the atmosphere does no net work on a wall of constant volume: the force
  // depends on the gauge pressure alone.
  MuscleBuild build = thin_walls(0.0);
  build.bladder_thickness_m = 0.254e-3;
  const double tb = build.bladder_thickness_m;
  const BraidGeometry geometry(build);
  const BladderLaw law = BladderLaw::thesis();
  for (double gauge : {35e3, 104e3, 276e3}) {  // the range of table 3.4
    for (double L : working_lengths()) {
      INFO("p = " << gauge << " Pa, L = " << L);
      const MuscleShape s = geometry.shape(L);
      const double newtonian = newtonian_fiber_tensions(geometry, s, law, gauge).force;
      const MuscleForces gauge_only = muscle_forces(geometry, s, law, kNoFriction, gauge, 0.0, 0.0);
      const MuscleForces with_atmosphere =
          muscle_forces(geometry, s, law, kNoFriction, kAtmosphere + gauge, kAtmosphere, 0.0);
      const double d_wall_3_1_3 = kPi * (s.diameter * tb - tb * tb) + kPi * L * tb * s.d_diameter;
      // Round-off only: 1e-12 of the largest term (the pressure force) the sum is made of.
      const double scale = gauge * 0.25 * kPi * s.diameter * s.diameter;
      REQUIRE(std::abs(gauge_only.bladder) > 1e-3 * std::abs(gauge_only.total));    // the bladder matters
      REQUIRE(std::abs(gauge * d_wall_3_1_3) > 1e-3 * std::abs(gauge_only.total));  // and so does the wall
      CHECK(std::abs(newtonian - (gauge_only.total + gauge * d_wall_3_1_3)) <= 1e-12 * scale);
      CHECK(std::abs(with_atmosphere.total - gauge_only.total) <= 1e-12 * scale);
    }
  }
}

TEST_CASE("At zero gauge pressure the gas and the atmosphere exert no force at any length", "[force][physics]") {
  // The invariant of a wall that conserves its volume: inside and outside pressures are equal,
  // so the gas and the atmosphere do equal and opposite work whatever the braid does.
  MuscleBuild build;  // PAM 2, with its cones and its 0.254 mm bladder
  const BraidGeometry geometry(build);
  for (double L : working_lengths()) {
    INFO("L = " << L);
    const MuscleForces f =
        muscle_forces(geometry, geometry.shape(L), BladderLaw::none(), kNoFriction, kAtmosphere, kAtmosphere, 0.0);
    CHECK(std::abs(f.pressure) <= 1e-12 * kAtmosphere * geometry.shape(L).total_volume / L);
  }
}

TEST_CASE("With the thesis's end cones the Newtonian force exceeds the virtual-work force",
          "[force][characterisation]") {
  // Characterisation, not a tolerance: the statement in force.hpp that the two formulations
  // part with cones (eq. 3.1.1's cones of fixed slant) must stay true. At 200 kPa gauge, thin
  // walls, no bladder, the Newtonian force is larger by ~21-23 N at every working length;
  // relative to the force that is +43 % at 0.17 m and +9 % at 0.22 m.
  const double gauge = 200e3;
  const BraidGeometry geometry(thin_walls(0.0095));
  std::ostringstream table;
  table << "Newtonian vs virtual-work force with cones (200 kPa, thin walls, no bladder)\n"
        << "  L [m]   F_vw [N]  F_newton [N]  diff [N]  diff/F_vw\n";
  for (double L : {0.16, 0.17, 0.18, 0.20, 0.22}) {
    const MuscleShape s = geometry.shape(L);
    const double vw =
        muscle_forces(geometry, s, BladderLaw::none(), kNoFriction, kAtmosphere + gauge, kAtmosphere, 0.0).total;
    const double newtonian = newtonian_fiber_tensions(geometry, s, BladderLaw::none(), gauge).force;
    table << std::fixed << std::setprecision(3) << "  " << L << std::setprecision(2) << std::setw(10) << vw
          << std::setw(14) << newtonian << std::setw(10) << newtonian - vw << std::setw(10) << std::setprecision(3)
          << (newtonian - vw) / vw << "\n";
    INFO("L = " << L << ": virtual work " << vw << " N, Newtonian " << newtonian << " N");
    CHECK(newtonian > vw);
    // Regression band around the 21-23 N the model gave when this test was written.
    CHECK(newtonian - vw > 15.0);
    CHECK(newtonian - vw < 30.0);
    if (L == 0.17) CHECK((newtonian - vw) / vw > 0.05);
  }
  WARN(table.str());
}
