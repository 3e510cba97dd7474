// Braid kinematics (thesis 3.1.1-3.1.3, 3.1.9-3.1.11): table 3.1, the derivatives the force and
// the gas equation rely on, and the closure of braid and cones.

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "pamkit/muscle/geometry.hpp"

namespace {

using namespace pamkit;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

// The thesis truncates some entries and rounds others (28.788 mm is printed 28.78, 29.057 mm is
// printed 29.06), so a reproduced value must lie within one unit of the printed last digit.
bool within_last_digit(double value, double printed, double unit) {
  return std::abs(value - printed) <= unit * (1.0 + 1e-9);
}

MuscleBuild flat_ends() {
  MuscleBuild b;
  b.cone_generator_m = 0.0;
  return b;
}

// Lengths spanning the default build's working range (min_length is 0.1355 m, max 0.2473 m).
std::vector<double> working_lengths() {
  std::vector<double> lengths;
  for (double L = 0.15; L <= 0.2200001; L += 0.005) lengths.push_back(L);
  return lengths;
}

}  // namespace

TEST_CASE("Table 3.1: theoretical bladder strains from the braid angles 25 and 50 degrees", "[geometry][thesis]") {
  // Rows of table 3.1 (thesis section 3.1.2): relaxed cylinder length [cm] and the printed
  // contracted diameter [mm], contracted length [cm] and circumferential strain.
  struct Row {
    double revolutions, relaxed_length_cm, contracted_diameter_mm, contracted_length_cm, strain_c;
  };
  const Row rows[] = {{1, 10.7, 28.78, 7.58, 0.863}, {2, 21.6, 29.06, 15.32, 0.881}, {3, 32.7, 29.32, 23.19, 0.898}};
  const double relaxed_diameter_mm = 15.45;  // table 3.1, the deflated bladder, the same for all three
  const double printed_strain_l = -0.290;    // table 3.1, all three rows

  for (const Row& row : rows) {
    INFO("n = " << row.revolutions);
    const double relaxed_length = row.relaxed_length_cm * 1e-2;
    const double fiber_length = relaxed_length / std::cos(25.0 * kDegree);  // eq. 3.1.10 at 25 deg
    REQUIRE(braid_cylinder_length(fiber_length, 25.0 * kDegree) == Approx(relaxed_length).epsilon(1e-14));

    const double contracted_diameter = braid_diameter(fiber_length, row.revolutions, 50.0 * kDegree);  // eq. 3.1.9
    const double contracted_length = braid_cylinder_length(fiber_length, 50.0 * kDegree);              // eq. 3.1.10
    const double strain_l = contracted_length / relaxed_length - 1.0;
    const double strain_c = contracted_diameter * 1e3 / relaxed_diameter_mm - 1.0;
    INFO("D = " << contracted_diameter * 1e3 << " mm, Lm = " << contracted_length * 1e2
                << " cm, strain L = " << strain_l << ", strain C = " << strain_c);

    CHECK(within_last_digit(contracted_diameter * 1e3, row.contracted_diameter_mm, 0.01));
    CHECK(within_last_digit(contracted_length * 1e2, row.contracted_length_cm, 0.01));
    CHECK(within_last_digit(strain_l, printed_strain_l, 0.001));
    CHECK(within_last_digit(strain_c, row.strain_c, 0.001));
    // Eq. 3.1.11 is eqs. 3.1.9-3.1.10 with the angle eliminated: it must give the fiber back.
    CHECK_REL(braid_fiber_length(contracted_length, contracted_diameter, row.revolutions), fiber_length, 1e-14);
  }
}

TEST_CASE("BraidGeometry: the deflated build is a shape of its own braid", "[geometry]") {
  // The fiber length is fixed from the deflated length and diameter, so shape(length_m) must
  // give the deflated diameter back (to the Newton solve's precision).
  for (const MuscleBuild& build : {MuscleBuild{}, flat_ends()}) {
    const BraidGeometry geometry(build);
    CHECK_REL(geometry.shape(build.length_m).diameter, build.diameter_m, 1e-12);
    CHECK_REL(geometry.shape(build.length_m).cylinder_length, geometry.deflated_cylinder_length(), 1e-12);
  }
}

TEST_CASE("BraidGeometry: braid and cone closures hold at every shape", "[geometry]") {
  for (const MuscleBuild& build : {MuscleBuild{}, flat_ends()}) {
    const BraidGeometry geometry(build);
    const double n = build.fiber_revolutions;
    for (double L : working_lengths()) {
      INFO("cone_generator_m = " << build.cone_generator_m << ", L = " << L);
      const MuscleShape s = geometry.shape(L);
      const double lym = geometry.fiber_length();
      // Eq. 3.1.11: the fibers over the cylinder are inextensible.
      CHECK_REL(std::pow(kPi * n * s.diameter, 2) + std::pow(s.cylinder_length, 2), lym * lym, 1e-12);
      // The length is the cylinder plus two cones, and each cone keeps its slant length.
      CHECK_REL(s.cylinder_length + 2.0 * s.cone_length, L, 1e-14);
      if (build.cone_generator_m > 0.0) {
        CHECK_REL(std::hypot(s.cone_length, 0.5 * (s.diameter - build.end_diameter_m)), build.cone_generator_m, 1e-12);
      } else {
        CHECK(s.cone_length == 0.0);
      }
      // Eqs. 3.1.9-3.1.10 at the angle the shape reports.
      CHECK_REL(braid_diameter(lym, n, s.braid_angle), s.diameter, 1e-12);
    }
  }
}

TEST_CASE("BraidGeometry: derivatives agree with central finite differences", "[geometry][derivatives]") {
  // Central differences with h = 1e-6 m: truncation error ~ h^2 f'''/6 ~ 1e-11 and the Newton
  // solve for D (converged to ~1e-15 relative) adds ~1e-16 m / h ~ 1e-10, so 1e-7 is ~1000x
  // above the expected error. dV/dL passes through zero near 54.7 deg (L ~ 0.15 m), so volume
  // derivatives are compared against the scale pi D^2 / 4 (dV/dL of a cylinder at fixed D) and
  // the dimensionless ones against 1.
  const double h = 1e-6;
  const double tolerance = 1e-7;
  using Field = double MuscleShape::*;
  struct Derivative {
    const char* name;
    Field value;
    Field derivative;
    bool is_volume;
  };
  const Derivative derivatives[] = {
      {"d_diameter", &MuscleShape::diameter, &MuscleShape::d_diameter, false},
      {"d_cylinder_length", &MuscleShape::cylinder_length, &MuscleShape::d_cylinder_length, false},
      {"d_total_volume", &MuscleShape::total_volume, &MuscleShape::d_total_volume, true},
      {"d_bladder_volume", &MuscleShape::bladder_volume, &MuscleShape::d_bladder_volume, true},
      {"d_gas_volume", &MuscleShape::gas_volume, &MuscleShape::d_gas_volume, true},
  };
  for (const MuscleBuild& build : {MuscleBuild{}, flat_ends()}) {
    const BraidGeometry geometry(build);
    for (double L : working_lengths()) {
      const MuscleShape s = geometry.shape(L);
      const MuscleShape up = geometry.shape(L + h);
      const MuscleShape down = geometry.shape(L - h);
      for (const Derivative& d : derivatives) {
        const double fd = (up.*d.value - down.*d.value) / (2.0 * h);
        const double reference = d.is_volume ? 0.25 * kPi * s.diameter * s.diameter : 1.0;
        INFO("cone_generator_m = " << build.cone_generator_m << ", L = " << L << ", " << d.name << ": analytic "
                                   << s.*d.derivative << ", finite difference " << fd);
        CHECK(std::abs(s.*d.derivative - fd) <= tolerance * reference);
      }
    }
  }
}

TEST_CASE("BraidGeometry: shape() rejects lengths outside the braid's range", "[geometry][validation]") {
  for (const MuscleBuild& build : {MuscleBuild{}, flat_ends()}) {
    const BraidGeometry geometry(build);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (double L : {geometry.min_length(), geometry.max_length(), geometry.min_length() - 1e-3,
                     geometry.max_length() + 1e-3, -0.1, nan}) {
      INFO("L = " << L);
      CHECK_THROWS_AS(geometry.shape(L), InvalidInput);
    }
    CHECK_THROWS_WITH(geometry.shape(geometry.max_length() + 1e-3), Catch::Contains("outside the range"));
    CHECK_NOTHROW(geometry.shape(0.5 * (geometry.min_length() + geometry.max_length())));
  }
}

TEST_CASE("BraidGeometry: a warm start from the last solve gives the cold start's shape", "[geometry][warm]") {
  // Both stop on the same Newton step test (2^-46 relative), after which one more step would
  // change D by ~(2^-46)^2: they agree to rounding, so 1e-14 relative (45x the double epsilon).
  for (const MuscleBuild& build : {MuscleBuild{}, flat_ends()}) {
    const BraidGeometry geometry(build);
    ShapeHint hint;
    // Up the working range and back down, as a stretch cycle visits it, then a jump across it.
    std::vector<double> lengths = working_lengths();
    lengths.insert(lengths.end(), lengths.rbegin(), lengths.rend());
    const double span = geometry.max_length() - geometry.min_length();
    lengths.push_back(geometry.min_length() + 1e-3 * span);
    lengths.push_back(geometry.max_length() - 1e-3 * span);
    for (double L : lengths) {
      INFO("cone_generator_m = " << build.cone_generator_m << ", L = " << L << ", hint from L = " << hint.length_m);
      const MuscleShape cold = geometry.shape(L);
      const MuscleShape warm = geometry.shape_from(hint, L, ShapeParts::all);
      CHECK_REL(warm.diameter, cold.diameter, 1e-14);
      // dD/dL is dimensionless and passes near zero as the cones flatten (its sensitivity to D
      // grows as 1 / LL^2): compared against 1, as the derivatives test compares it.
      CHECK(std::abs(warm.d_diameter - cold.d_diameter) <= 1e-12);
      CHECK_REL(warm.gas_volume, cold.gas_volume, 1e-13);
      CHECK_REL(warm.braid_angle, cold.braid_angle, 1e-13);
      // The hint now holds this solve, for the next one.
      CHECK(hint.length_m == L);
      CHECK(hint.diameter_m == warm.diameter);
      CHECK(hint.d_diameter == warm.d_diameter);
    }
  }
}

TEST_CASE("BraidGeometry: the kinematic parts leave the angles out and the rest unchanged", "[geometry][warm]") {
  const BraidGeometry geometry{MuscleBuild{}};
  for (double L : working_lengths()) {
    INFO("L = " << L);
    ShapeHint all_hint;
    ShapeHint kinematic_hint;
    const MuscleShape all = geometry.shape_from(all_hint, L, ShapeParts::all);
    const MuscleShape kinematic = geometry.shape_from(kinematic_hint, L, ShapeParts::kinematics);
    CHECK(std::isnan(kinematic.braid_angle));
    CHECK(std::isnan(kinematic.end_braid_angle));
    CHECK(std::isnan(kinematic.cone_angle));
    CHECK(std::isnan(kinematic.mean_braid_angle));
    // The same solve from the same (empty) hint: identical bits for everything the rates use.
    CHECK(kinematic.diameter == all.diameter);
    CHECK(kinematic.cylinder_length == all.cylinder_length);
    CHECK(kinematic.d_diameter == all.d_diameter);
    CHECK(kinematic.d_cylinder_length == all.d_cylinder_length);
    CHECK(kinematic.gas_volume == all.gas_volume);
    CHECK(kinematic.d_gas_volume == all.d_gas_volume);
    CHECK(kinematic.d_total_volume == all.d_total_volume);
  }
  ShapeHint hint;
  CHECK_THROWS_AS(geometry.shape_from(hint, geometry.max_length() + 1e-3, ShapeParts::kinematics), InvalidInput);
}
