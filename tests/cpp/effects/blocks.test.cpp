// A sealed test simulated in blocks (simulate_measurement_blocks): what a long test's
// `pamkit simulate` streams to its CSV.

#include <cstddef>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "effect_test_support.hpp"

using namespace pamkit_test;

namespace {

// The thesis's bench: two cycles to 50 mm at 2.5 mm/s with 2 s holds, at 0.1 s (881 samples).
ElongationTrajectory bench() { return thesis_protocol(0.05, 2.5e-3, 2, 0.1, 2.0); }

/// simulate_measurement_blocks's blocks joined, each checked to follow the one before.
Measurement joined_blocks(const std::vector<EffectPtr>& effects, std::size_t block_size) {
  Measurement joined;
  const auto append = [&joined](std::size_t first, const Measurement& block) {
    CHECK(first == joined.time_s.size());
    joined.time_s.insert(joined.time_s.end(), block.time_s.begin(), block.time_s.end());
    joined.elongation_m.insert(joined.elongation_m.end(), block.elongation_m.begin(), block.elongation_m.end());
    joined.force_N.insert(joined.force_N.end(), block.force_N.begin(), block.force_N.end());
    joined.gauge_pressure_Pa.insert(joined.gauge_pressure_Pa.end(), block.gauge_pressure_Pa.begin(),
                                    block.gauge_pressure_Pa.end());
    joined.temperature_K.insert(joined.temperature_K.end(), block.temperature_K.begin(), block.temperature_K.end());
  };
  joined.statistics =
      simulate_measurement_blocks(MuscleParams(), table_c2_90(), bench(), effects, Simulator(), block_size, append);
  return joined;
}

}  // namespace

TEST_CASE("blocks: a sealed test in blocks is simulate_measurement's, bit for bit", "[effects][blocks]") {
  // No effect; physics and motion effects (fixture slack moves the muscle off the crosshead).
  const std::vector<std::vector<EffectPtr>> cases{
      {}, {effect("heat_transfer:time_constant_s=2"), effect("fixture_slack:slack_m=0.001")}};
  for (const std::vector<EffectPtr>& effects : cases) {
    INFO(effects.size() << " effects");
    const Measurement whole = simulate_measurement(MuscleParams(), table_c2_90(), bench(), effects);
    for (const std::size_t block_size : {std::size_t{1}, std::size_t{100}, std::size_t{5000}}) {
      INFO("blocks of " << block_size);
      const Measurement joined = joined_blocks(effects, block_size);
      CHECK(identical(joined, whole));
      CHECK(joined.statistics.steps == whole.statistics.steps);
      CHECK(joined.statistics.restarts == whole.statistics.restarts);
    }
  }
  // The slack changes what the muscle does, and the elongation reported is still the crosshead's.
  const Measurement slack = joined_blocks(cases[1], 64);
  CHECK(identical(slack.elongation_m, bench().elongation()));
  CHECK_FALSE(identical(slack.force_N, joined_blocks({}, 64).force_N));
}

TEST_CASE("blocks: an effect on the measured channels is refused, named", "[effects][blocks]") {
  // A lag filter needs the samples before a block, a skew the ones after, a sensor's response
  // the whole record: no effect of the catalog on the measured channels acts on one block alone.
  std::size_t measured = 0;
  for (const std::string& name : EffectCatalog::builtin().names()) {
    if (effect(name)->stage() != EffectStage::measurement) continue;
    ++measured;
    INFO(name);
    CHECK_THROWS_WITH(simulate_measurement_blocks(MuscleParams(), table_c2_90(), bench(), {effect(name)}, Simulator(),
                                                  100, [](std::size_t, const Measurement&) {}),
                      name +
                          " acts on the whole measured series, which a simulation in blocks never holds: "
                          "simulate the whole measurement for it");
  }
  CHECK(measured >= 5);  // the lag, the skew, the transducer, the load cell, the thermometer
}
