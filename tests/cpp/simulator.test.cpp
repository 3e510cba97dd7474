// The simulator as a piece of software: re-entrant across threads, its solver statistics, the
// model's warm-started evaluation and the output path.

#include <cmath>
#include <cstddef>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "pamkit/sim/simulator.hpp"

namespace {

using namespace pamkit;

struct Case {
  MuscleParams params;
  InitialState initial;
  ElongationTrajectory trajectory;
};

// Four different runs: the gas processes, a friction sharpness, pressures of table C.1-C.3,
// protocols with and without holds.
std::vector<Case> four_cases() {
  std::vector<Case> cases;
  MuscleParams polytropic;
  cases.push_back({polytropic, {0.167, 236.63e3}, thesis_protocol(0.04, 2.5e-3, 2)});
  MuscleParams heat;
  heat.gas.process = GasProcess::heat_transfer;
  heat.gas.heat_transfer_time_constant_s = 2.0;
  cases.push_back({heat, {0.170, 138e3}, thesis_protocol(0.03, 5e-3, 3, 0.05, 1.0)});
  MuscleParams sharp;
  sharp.friction.sharpness_s_per_m = 200.0;
  sharp.gas.polytropic_index = 1.3;
  cases.push_back({sharp, {0.167, 207e3}, thesis_protocol(0.045, 2.5e-3, 1)});
  MuscleParams low;
  low.build.length_m = 0.223;
  low.gas.process = GasProcess::heat_transfer;
  cases.push_back({low, {0.185, 35e3}, thesis_protocol(0.03, 1e-2, 4)});
  return cases;
}

// Bit-for-bit equality of every series: the runs share nothing but the const Simulator.
void check_identical(const SimulationResult& a, const SimulationResult& b) {
  CHECK(a.time_s == b.time_s);
  CHECK(a.length_m == b.length_m);
  CHECK(a.force_N == b.force_N);
  CHECK(a.friction_force_N == b.friction_force_N);
  CHECK(a.pressure_gauge_Pa == b.pressure_gauge_Pa);
  CHECK(a.temperature_K == b.temperature_K);
  CHECK(a.gas_volume_m3 == b.gas_volume_m3);
  CHECK(a.work_J == b.work_J);
  CHECK(a.heat_lost_J == b.heat_lost_J);
  CHECK(a.friction_dissipated_J == b.friction_dissipated_J);
  CHECK(a.statistics.steps == b.statistics.steps);
  CHECK(a.statistics.rhs_evaluations == b.statistics.rhs_evaluations);
}

}  // namespace

TEST_CASE("Simulator: one shared simulator runs four models in parallel threads", "[sim][threads]") {
  const std::vector<Case> cases = four_cases();
  std::vector<MuscleModel> models;
  for (const Case& c : cases) models.emplace_back(c.params, c.initial);
  const Simulator simulator;

  std::vector<SimulationResult> serial;
  for (std::size_t i = 0; i < cases.size(); ++i) serial.push_back(simulator.run(models[i], cases[i].trajectory));

  std::vector<SimulationResult> parallel(cases.size());
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    threads.emplace_back([&, i] { parallel[i] = simulator.run(models[i], cases[i].trajectory); });
  }
  for (std::thread& t : threads) t.join();

  for (std::size_t i = 0; i < cases.size(); ++i) {
    INFO("case " << i);
    REQUIRE(parallel[i].time_s.size() == cases[i].trajectory.size());
    check_identical(parallel[i], serial[i]);
  }
  // The four runs differ, so identical results are not a property of the inputs.
  CHECK(serial[0].force_N.back() != serial[1].force_N.back());
  CHECK(serial[2].temperature_K[10] != serial[3].temperature_K[10]);
}

TEST_CASE("Simulator: solver statistics are filled", "[sim][statistics]") {
  const MuscleModel model(MuscleParams{}, InitialState{0.167, 236.63e3});
  const Simulator simulator;
  for (int cycles : {1, 2, 5}) {
    INFO(cycles << " cycles");
    const SimulationResult r = simulator.run(model, thesis_protocol(0.05, 2.5e-3, cycles));
    const SolverStatistics& s = r.statistics;
    CHECK(s.steps > 0);
    CHECK(s.rhs_evaluations >= s.steps);  // at least one evaluation per step
    CHECK(s.nonlinear_iterations >= s.steps);
    CHECK(s.linear_solver_setups > 0);
    // A triangle wave without holds turns at every top and every bottom but the last.
    CHECK(s.restarts == 2 * cycles - 1);
  }
  // With holds each cycle has four corners: up, hold, down, hold; the last hold ends the run.
  const SimulationResult held = simulator.run(model, thesis_protocol(0.05, 2.5e-3, 2, 0.1, 2.0));
  CHECK(held.statistics.restarts == 4 * 2 - 1);
}

TEST_CASE("MuscleModel: a warm-started evaluation gives the cold one's outputs", "[sim][warm]") {
  // evaluate_with starts the braid's closure from the workspace's last solve; the Newton solve
  // stops on the same test either way (2^-46 relative), so every output agrees to ~1e-13
  // (the rates' subtractions, gauge pressure and force, lose two digits of the diameter's 1e-15).
  MuscleParams plain;
  plain.gas.process = GasProcess::heat_transfer;
  MuscleParams extended = plain;
  extended.extensions.fiber_compliance_per_N = 1e-4;  // the braid length solve calls the geometry too
  extended.extensions.viscoelastic_strength = 0.3;
  for (const MuscleParams& params : {plain, extended}) {
    const MuscleModel model(params, InitialState{0.167, 236.63e3});
    MuscleWorkspace workspace;
    State y = model.initial();
    y[State::temperature_K] = 300.0;
    y[State::viscous_stress_l_Pa] = 1e3;
    for (double elongation = 0.0; elongation <= 0.0523; elongation += 2.5e-4) {
      const double length = 0.167 + elongation;
      INFO("fiber compliance " << params.extensions.fiber_compliance_per_N << ", L = " << length);
      const MuscleOutputs cold = model.evaluate(length, 2.5e-3, y);
      const MuscleOutputs warm = model.evaluate_with(workspace, length, 2.5e-3, y, ShapeParts::kinematics);
      CHECK_REL(warm.forces.total, cold.forces.total, 1e-12);
      CHECK_REL(warm.gauge_pressure_Pa, cold.gauge_pressure_Pa, 1e-13);
      CHECK_REL(warm.braid_length_m, cold.braid_length_m, 1e-14);
      for (int i = 0; i < State::size; ++i) {
        INFO("rate " << i);
        CHECK(std::abs(warm.rate[i] - cold.rate[i]) <= 1e-12 * std::abs(cold.rate[i]) + 1e-300);
      }
      CHECK(std::isnan(warm.shape.braid_angle));
      CHECK(!std::isnan(cold.shape.braid_angle));
    }
  }
}
