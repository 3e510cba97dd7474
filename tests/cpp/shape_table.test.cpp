// The shape table (sim/shape_table.hpp): the braid's shapes along a trajectory solved once, read
// by the runs it applies to and ignored by the others.

#include <cmath>
#include <cstddef>
#include <cstring>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "pamkit/sim/shape_table.hpp"
#include "pamkit/sim/simulator.hpp"

namespace {

using namespace pamkit;

// Bit-for-bit equality (not ==, which takes -0.0 for 0.0).
bool identical(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

// Every output column of two runs, bit for bit.
void check_identical(const SimulationResult& a, const SimulationResult& b) {
  CHECK(identical(a.length_m, b.length_m));
  CHECK(identical(a.force_N, b.force_N));
  CHECK(identical(a.friction_force_N, b.friction_force_N));
  CHECK(identical(a.gauge_pressure_Pa, b.gauge_pressure_Pa));
  CHECK(identical(a.temperature_K, b.temperature_K));
  CHECK(identical(a.gas_volume_m3, b.gas_volume_m3));
  CHECK(identical(a.gas_mass_kg, b.gas_mass_kg));
  CHECK(identical(a.braid_angle_rad, b.braid_angle_rad));
  CHECK(identical(a.diameter_m, b.diameter_m));
  CHECK(identical(a.work_J, b.work_J));
  CHECK(identical(a.heat_lost_J, b.heat_lost_J));
  CHECK(identical(a.friction_dissipated_J, b.friction_dissipated_J));
  CHECK(a.statistics.steps == b.statistics.steps);
  CHECK(a.statistics.rhs_evaluations == b.statistics.rhs_evaluations);
}

// A sealed test with heat transfer and the thesis's friction (table C.4), on the bench protocol
// with holds: corners, restarts and a temperature that relaxes.
MuscleParams heat_and_friction() {
  MuscleParams params;
  params.gas.process = GasProcess::heat_transfer;
  params.gas.heat_transfer_time_constant_s = 2.0;
  return params;
}
const InitialState kInitial{0.170, 138e3};
ElongationTrajectory bench() { return thesis_protocol(0.03, 5e-3, 3, 0.05, 1.0); }

}  // namespace

TEST_CASE("ShapeTable: each sample's shape is the closure's, to its Newton tolerance", "[sim][shape_table]") {
  const ElongationTrajectory trajectory = bench();
  const MuscleBuild build;
  const ShapeTable table(build, kInitial.length_m, trajectory);
  REQUIRE(table.size() == trajectory.size());
  const BraidGeometry geometry(build);
  for (std::size_t k = 0; k < table.size(); ++k) {
    INFO("sample " << k);
    const double length = kInitial.length_m + trajectory.elongation()[k];
    CHECK(table.length_m()[k] == length);
    const MuscleShape cold = geometry.shape(length);
    const MuscleShape& tabulated = table.shape(k);
    CHECK(tabulated.length == length);
    // The warm-started closure stops within Boost's Newton tolerance (digits - 6 = 47 bits,
    // about 7e-15 relative) of the cold solve: the bounds of geometry.test.cpp's warm start.
    CHECK_REL(tabulated.diameter, cold.diameter, 1e-14);
    CHECK_REL(tabulated.gas_volume, cold.gas_volume, 1e-13);
    CHECK_REL(tabulated.braid_angle, cold.braid_angle, 1e-13);
    // Only the cylinder's braid angle is tabulated: the others stay NaN, so a misuse shows.
    CHECK(std::isnan(tabulated.mean_braid_angle));
  }
}

TEST_CASE("ShapeTable: a run that reads the table is the run without it, bit for bit", "[sim][shape_table]") {
  // Bit for bit, not to a tolerance: the table solves the closures in the order, from the same
  // warm starts and with the same ShapeParts as the run's output path, and the model computes
  // every other output from the shape by the same operations (MuscleModel::evaluate_at_shape).
  const ElongationTrajectory trajectory = bench();
  const MuscleModel model(heat_and_friction(), kInitial);
  const ShapeTable table(model.params().build, kInitial.length_m, trajectory);
  REQUIRE(table.applies_to(model, trajectory));
  const Simulator simulator;
  const SimulationResult plain = simulator.run(model, trajectory);
  const SimulationResult tabulated = simulator.run(model, trajectory, &table);
  check_identical(tabulated, plain);
  CHECK(plain.statistics.tabulated_shapes == 0);
  CHECK(tabulated.statistics.tabulated_shapes == static_cast<long>(trajectory.size()));
  CHECK(tabulated.statistics.output_evaluations == static_cast<long>(trajectory.size()));
  // The friction is on (the comparison covers it) and the gas exchanges heat.
  CHECK(std::abs(plain.friction_force_N[10]) > 0.0);
  CHECK(plain.heat_lost_J.back() != 0.0);

  // The same in blocks, and from two threads sharing the one table.
  SimulationResult joined = plain;
  const SolverStatistics statistics = simulator.run_blocks(
      model, trajectory, 100,
      [&joined](std::size_t first, const SimulationResult& block) {
        std::copy(block.force_N.begin(), block.force_N.end(), joined.force_N.begin() + static_cast<long>(first));
      },
      &table);
  CHECK(identical(joined.force_N, plain.force_N));
  CHECK(statistics.tabulated_shapes == static_cast<long>(trajectory.size()));
  std::vector<SimulationResult> shared(2);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < shared.size(); ++i) {
    threads.emplace_back([&, i] { shared[i] = simulator.run(model, trajectory, &table); });
  }
  for (std::thread& thread : threads) thread.join();
  for (const SimulationResult& run : shared) check_identical(run, plain);
}

TEST_CASE("ShapeTable: a table that does not apply is ignored, the shapes solved", "[sim][shape_table]") {
  const ElongationTrajectory trajectory = bench();
  const Simulator simulator;
  const MuscleParams params = heat_and_friction();

  MuscleBuild other_build = params.build;
  other_build.fiber_thickness_m *= 1.001;  // not read by the closure, but the table compares every field
  const ElongationTrajectory shorter = thesis_protocol(0.03, 5e-3, 2, 0.05, 1.0);
  std::vector<double> shifted = trajectory.elongation();
  shifted.back() += 1e-9;  // one sample's length off
  MuscleParams compliant = params;
  compliant.extensions.fiber_compliance_per_N = 1e-4;

  struct Mismatch {
    const char* what;
    MuscleParams params;
    ShapeTable table;
  };
  const std::vector<Mismatch> mismatches{
      {"another build", params, ShapeTable(other_build, kInitial.length_m, trajectory)},
      {"another initial length", params, ShapeTable(params.build, kInitial.length_m + 1e-4, trajectory)},
      {"another trajectory's size", params, ShapeTable(params.build, kInitial.length_m, shorter)},
      {"one sample's length", params,
       ShapeTable(params.build, kInitial.length_m, ElongationTrajectory(trajectory.time(), shifted))},
      {"compliant fibers", compliant, ShapeTable(params.build, kInitial.length_m, trajectory)},
  };
  for (const Mismatch& m : mismatches) {
    INFO(m.what);
    const MuscleModel model(m.params, kInitial);
    CHECK_FALSE(m.table.applies_to(model, trajectory));
    const SimulationResult plain = simulator.run(model, trajectory);
    const SimulationResult with_table = simulator.run(model, trajectory, &m.table);
    CHECK(with_table.statistics.tabulated_shapes == 0);
    check_identical(with_table, plain);
  }
}

TEST_CASE("ShapeTable: bad input is named", "[sim][shape_table]") {
  // An elongation that takes the muscle past the braid's longest length, named by its sample.
  const ElongationTrajectory too_far({0.0, 1.0, 2.0}, {0.0, 0.01, 1.0});
  CHECK_THROWS_WITH(ShapeTable(MuscleBuild{}, 0.167, too_far),
                    Catch::Contains("sample 2") && Catch::Contains("outside the braid's range"));
  MuscleBuild bad;
  bad.fiber_count = 1.0;
  CHECK_THROWS_AS(ShapeTable(bad, 0.167, bench()), InvalidParameter);
  // A shape fixed beforehand cannot serve compliant fibers, whose braid length the force sets.
  MuscleParams compliant;
  compliant.extensions.fiber_compliance_per_N = 1e-4;
  const MuscleModel model(compliant, {0.167, 236.63e3});
  CHECK_THROWS_WITH(model.evaluate_at_shape(BraidGeometry(compliant.build).shape(0.17), 0.0, model.initial()),
                    Catch::Contains("fiber_compliance_per_N"));
}
