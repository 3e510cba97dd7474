// A sealed test's simulated measurement with a shape table (simulate_measurement's `shapes`): read
// where the effects leave the build, the motion and the fibers as the table has them, ignored
// where they do not.

#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "effect_test_support.hpp"
#include "pamkit/sim/shape_table.hpp"

using namespace pamkit_test;

namespace {

// The thesis's bench: two cycles to 50 mm at 2.5 mm/s with 2 s holds, at 0.1 s (881 samples).
ElongationTrajectory bench() { return thesis_protocol(0.05, 2.5e-3, 2, 0.1, 2.0); }

}  // namespace

TEST_CASE("shape table: a sealed run with heat transfer and friction reads it, same bits", "[effects][shape_table]") {
  // The default MuscleParams carry the thesis's friction (table C.4); the effects add heat
  // transfer and a dead volume, which change the gas, not the braid. Bit for bit: the table
  // solves the shapes as the run's output path does (tests/cpp/shape_table.test.cpp).
  const std::vector<EffectPtr> effects{effect("heat_transfer:time_constant_s=2"), effect("dead_volume")};
  const ShapeTable table(MuscleParams().build, table_c2_90().length_m, bench());
  const Measurement plain = simulate_measurement(MuscleParams(), table_c2_90(), bench(), effects);
  const Measurement tabulated =
      simulate_measurement(MuscleParams(), table_c2_90(), bench(), effects, Simulator(), &table);
  CHECK(identical(tabulated, plain));
  CHECK(plain.statistics.tabulated_shapes == 0);
  CHECK(tabulated.statistics.tabulated_shapes == static_cast<long>(bench().size()));
  // In blocks too.
  Measurement joined;
  const SolverStatistics statistics = simulate_measurement_blocks(
      MuscleParams(), table_c2_90(), bench(), effects, Simulator(), 100,
      [&joined](std::size_t, const Measurement& block) {
        joined.force_N.insert(joined.force_N.end(), block.force_N.begin(), block.force_N.end());
      },
      &table);
  CHECK(identical(joined.force_N, plain.force_N));
  CHECK(statistics.tabulated_shapes == static_cast<long>(bench().size()));
}

TEST_CASE("shape table: effects that move the muscle or stretch its fibers leave it unread", "[effects][shape_table]") {
  // Fixture slack moves the muscle off the crosshead, so its lengths are not the table's;
  // compliant fibers make the braid's shape depend on their tension, so on the gas. The run then solves its
  // shapes and is the plain run, bit for bit.
  const ShapeTable crosshead_table(MuscleParams().build, table_c2_90().length_m, bench());
  for (const std::string spec : {"fixture_slack:slack_m=0.001", "fiber_compliance"}) {
    INFO(spec);
    const std::vector<EffectPtr> effects{effect(spec)};
    const Measurement plain = simulate_measurement(MuscleParams(), table_c2_90(), bench(), effects);
    const Measurement with_table =
        simulate_measurement(MuscleParams(), table_c2_90(), bench(), effects, Simulator(), &crosshead_table);
    CHECK(with_table.statistics.tabulated_shapes == 0);
    CHECK(identical(with_table, plain));
  }
  // A table built along the slack fixture's own motion applies to it.
  const EffectPtr slack = effect("fixture_slack:slack_m=0.001");
  const ElongationTrajectory moved(bench().time(), slack->apply_to_elongation(bench().time(), bench().elongation()));
  const ShapeTable moved_table(MuscleParams().build, table_c2_90().length_m, moved);
  const Measurement plain = simulate_measurement(MuscleParams(), table_c2_90(), bench(), {slack});
  const Measurement tabulated =
      simulate_measurement(MuscleParams(), table_c2_90(), bench(), {slack}, Simulator(), &moved_table);
  CHECK(tabulated.statistics.tabulated_shapes == static_cast<long>(bench().size()));
  CHECK(identical(tabulated, plain));
}

TEST_CASE("shape table: a table of another build is unread", "[effects][shape_table]") {
  MuscleParams longer;
  longer.build.length_m = 0.226;
  const ShapeTable table(longer.build, table_c2_90().length_m, bench());
  const Measurement plain = simulate_measurement(MuscleParams(), table_c2_90(), bench(), {});
  const Measurement with_table = simulate_measurement(MuscleParams(), table_c2_90(), bench(), {}, Simulator(), &table);
  CHECK(with_table.statistics.tabulated_shapes == 0);
  CHECK(identical(with_table, plain));
}
