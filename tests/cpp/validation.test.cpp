// Every public entry checks its input and says which field or sample is wrong.

#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "pamkit/muscle/free_inflation.hpp"
#include "pamkit/sim/simulator.hpp"

namespace {

using namespace pamkit;
using Catch::Contains;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// For each field the structure declares: a value below its range, above it, and NaN must each
// throw InvalidParameter naming "Struct.field"; the range's own ends must be accepted when
// `check_bounds_accepted` (MuscleBuild's relational checks reject some of its range ends).
template <class Struct>
void check_every_field(bool check_bounds_accepted) {
  Struct::for_each_field([&](const char* name, auto member, const FieldInfo& info) {
    const std::string qualified = std::string(Struct::kName) + "." + name;
    using Field = std::remove_reference_t<decltype(std::declval<Struct&>().*member)>;
    // An enumeration's range spans its enumerators' values: an integer just outside (a stray
    // cast) is out of range; NaN has no enumeration counterpart.
    auto assign = [&](Struct& object, double value) {
      if constexpr (std::is_enum_v<Field>) {
        object.*member = static_cast<Field>(static_cast<std::underlying_type_t<Field>>(value));
      } else {
        object.*member = value;
      }
    };
    std::vector<double> bad_values{info.min - 0.5 * std::abs(info.min) - 1.0, 2.0 * info.max + 1.0};
    if (!std::is_enum_v<Field>) bad_values.push_back(kNaN);
    for (double bad : bad_values) {
      Struct object;
      assign(object, bad);
      INFO(qualified << " = " << bad);
      CHECK_THROWS_AS(object.validate(), InvalidParameter);
      CHECK_THROWS_WITH(object.validate(), Contains(qualified));
    }
    if (check_bounds_accepted) {
      for (double edge : {info.min, info.max}) {
        Struct object;
        assign(object, edge);
        INFO(qualified << " = " << edge << " (a bound of its range, inclusive)");
        CHECK_NOTHROW(object.validate());
      }
    }
  });
}

MuscleBuild build_with(void (*change)(MuscleBuild&)) {
  MuscleBuild b;
  change(b);
  return b;
}

}  // namespace

TEST_CASE("Defaults are valid", "[validation]") {
  CHECK_NOTHROW(MuscleBuild{}.validate());
  CHECK_NOTHROW(FrictionParams{}.validate());
  CHECK_NOTHROW(GasParams{}.validate());
  CHECK_NOTHROW(InitialState{}.validate());
  CHECK_NOTHROW(SimulatorConfig{}.validate());
  CHECK_NOTHROW(MuscleParams{}.validate());
}

TEST_CASE("Parameter ranges: out of range and NaN throw InvalidParameter naming the field", "[validation]") {
  SECTION("MuscleBuild") { check_every_field<MuscleBuild>(false); }
  SECTION("FrictionParams") { check_every_field<FrictionParams>(true); }
  SECTION("GasParams") { check_every_field<GasParams>(true); }
  SECTION("InitialState") { check_every_field<InitialState>(true); }
  SECTION("SimulatorConfig") { check_every_field<SimulatorConfig>(true); }
}

TEST_CASE("MuscleBuild: relations between fields", "[validation]") {
  // The bladder must fit inside the braid.
  const MuscleBuild wide_bladder = build_with([](MuscleBuild& b) { b.bladder_diameter_m = 0.021; });
  CHECK_THROWS_AS(wide_bladder.validate(), InvalidParameter);
  CHECK_THROWS_WITH(wide_bladder.validate(), Contains("MuscleBuild.bladder_diameter_m"));

  // Walls 2 (8 + 0.254) mm thick leave no gas space in a 15.45 mm bladder.
  const MuscleBuild thick_walls = build_with([](MuscleBuild& b) { b.bladder_thickness_m = 0.008; });
  CHECK_THROWS_AS(thick_walls.validate(), InvalidParameter);
  CHECK_THROWS_WITH(thick_walls.validate(), Contains("MuscleBuild.bladder_thickness_m"));

  // The cones narrow from the braid to the caps, so the caps must be narrower.
  const MuscleBuild wide_caps = build_with([](MuscleBuild& b) { b.end_diameter_m = 0.020; });
  CHECK_THROWS_AS(wide_caps.validate(), InvalidParameter);
  CHECK_THROWS_WITH(wide_caps.validate(), Contains("MuscleBuild.end_diameter_m"));

  // A 3 mm slant cannot span (20 - 13) / 2 = 3.5 mm of radius.
  const MuscleBuild short_cones = build_with([](MuscleBuild& b) { b.cone_generator_m = 0.003; });
  CHECK_THROWS_AS(short_cones.validate(), InvalidParameter);
  CHECK_THROWS_WITH(short_cones.validate(), Contains("MuscleBuild.cone_generator_m"));

  // Two 0.2 m cones do not fit in 0.225 m.
  const MuscleBuild long_cones = build_with([](MuscleBuild& b) { b.cone_generator_m = 0.2; });
  CHECK_THROWS_AS(long_cones.validate(), InvalidParameter);
  CHECK_THROWS_WITH(long_cones.validate(), Contains("MuscleBuild.cone_generator_m"));

  // With flat ends the caps' diameter constrains nothing.
  const MuscleBuild flat_wide_caps = build_with([](MuscleBuild& b) {
    b.cone_generator_m = 0.0;
    b.end_diameter_m = 0.030;
  });
  CHECK_NOTHROW(flat_wide_caps.validate());

  // Every constructor that takes a build validates it.
  CHECK_THROWS_AS(BraidGeometry(wide_bladder), InvalidParameter);
  MuscleParams params;
  params.build = short_cones;
  CHECK_THROWS_AS(MuscleModel(params, InitialState{}), InvalidParameter);
}

TEST_CASE("ElongationTrajectory rejects bad samples and names the index", "[validation][trajectory]") {
  using V = std::vector<double>;
  CHECK_THROWS_AS(ElongationTrajectory(V{0, 1, 1}, V{0, 0, 0}), InvalidInput);
  CHECK_THROWS_WITH(ElongationTrajectory(V{0, 1, 1}, V{0, 0, 0}), Contains("time_s[2]"));
  CHECK_THROWS_WITH(ElongationTrajectory(V{0, 2, 1}, V{0, 0, 0}), Contains("time_s[2]"));
  CHECK_THROWS_WITH(ElongationTrajectory(V{0, kNaN, 2}, V{0, 0, 0}), Contains("time_s[1]"));
  CHECK_THROWS_WITH(ElongationTrajectory(V{0, 1, 2}, V{0, 0, kNaN}), Contains("elongation_m[2]"));
  CHECK_THROWS_WITH(ElongationTrajectory(V{0, 1, 2}, V{0, std::numeric_limits<double>::infinity(), 0}),
                    Contains("elongation_m[1]"));
  CHECK_THROWS_AS(ElongationTrajectory(V{0, 1, 2}, V{0, 0}), InvalidInput);
  CHECK_THROWS_WITH(ElongationTrajectory(V{0, 1, 2}, V{0, 0}), Contains("3 times but 2 elongations"));
  CHECK_THROWS_AS(ElongationTrajectory(V{0}, V{0}), InvalidInput);
  CHECK_THROWS_WITH(ElongationTrajectory(V{0}, V{0}), Contains("at least 2 samples"));
  CHECK_THROWS_AS(ElongationTrajectory(V{}, V{}), InvalidInput);
  CHECK_NOTHROW(ElongationTrajectory(V{0, 1}, V{0, -0.01}));

  CHECK_THROWS_WITH(thesis_protocol(0.0), Contains("max_elongation_m"));
  CHECK_THROWS_WITH(thesis_protocol(0.05, -1.0), Contains("speed_m_per_s"));
  CHECK_THROWS_WITH(thesis_protocol(0.05, 2.5e-3, 0), Contains("cycles"));
  CHECK_THROWS_WITH(thesis_protocol(0.05, 2.5e-3, 1, kNaN), Contains("sample_period_s"));
  CHECK_THROWS_WITH(thesis_protocol(0.05, 2.5e-3, 1, 0.1, -1.0), Contains("hold_s"));
}

TEST_CASE("Simulator and model reject lengths outside the braid's range", "[validation][sim]") {
  const MuscleModel model(MuscleParams{}, InitialState{0.167, 236.63e3});
  const double max_length = model.geometry().max_length();  // 0.2473 m for the default build
  // Sample 2 stretches the muscle 1 cm beyond its longest length.
  const double too_far = max_length - 0.167 + 0.01;
  const ElongationTrajectory trajectory({0.0, 1.0, 2.0, 3.0}, {0.0, 0.01, too_far, 0.0});
  const Simulator simulator;
  CHECK_THROWS_AS(simulator.run(model, trajectory), InvalidInput);
  CHECK_THROWS_WITH(simulator.run(model, trajectory), Contains("trajectory sample 2"));
  // The message points at the usual culprit: a record re-zeroed mid-stretch.
  CHECK_THROWS_WITH(simulator.run(model, trajectory), Contains("initial_length_m"));

  // Below the shortest length (the cones flatten at 0.1355 m).
  const ElongationTrajectory too_short({0.0, 1.0}, {0.0, -0.05});
  CHECK_THROWS_WITH(simulator.run(model, too_short), Contains("trajectory sample 1"));

  CHECK_THROWS_AS(MuscleModel(MuscleParams{}, InitialState{0.30, 100e3}), InvalidInput);
  CHECK_THROWS_AS(MuscleModel(MuscleParams{}, InitialState{0.10, 100e3}), InvalidInput);
  CHECK_THROWS_AS(MuscleModel(MuscleParams{}, InitialState{0.167, -1.0}), InvalidParameter);
  CHECK_THROWS_WITH(MuscleModel(MuscleParams{}, InitialState{0.167, -1.0}), Contains("InitialState.gauge_pressure_Pa"));

  SimulatorConfig config;
  config.relative_tolerance = 0.0;
  CHECK_THROWS_AS(Simulator(config), InvalidParameter);
  CHECK_THROWS_WITH(Simulator(config), Contains("SimulatorConfig.relative_tolerance"));
}

TEST_CASE("free_inflation rejects a negative or NaN pressure", "[validation][free_inflation]") {
  const BraidGeometry geometry{MuscleBuild{}};
  CHECK_THROWS_AS(free_inflation(geometry, BladderLaw::thesis(), 101e3, -1.0), InvalidInput);
  CHECK_THROWS_AS(free_inflation(geometry, BladderLaw::thesis(), 101e3, kNaN), InvalidInput);
}
