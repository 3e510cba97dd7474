// Simulator::run_batch: each run's channels and extremes are Simulator::run's bit for bit,
// whatever the number of threads; a run that fails fails alone; ParameterSets makes the muscle a
// caller would make by hand; bad requests are refused by name.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "pamkit/sim/shape_table.hpp"
#include "pamkit/sim/simulator.hpp"

namespace {

using namespace pamkit;

/// Table C.2's muscle at `pressure_Pa`, its gas exchanging heat in `tau_s` (polytropic if 0).
MuscleModel muscle(double pressure_Pa, double tau_s, double length_m = 0.167) {
  MuscleParams params;
  if (tau_s > 0.0) {
    params.gas.process = GasProcess::heat_transfer;
    params.gas.heat_transfer_time_constant_s = tau_s;
  }
  return MuscleModel(params, InitialState{length_m, pressure_Pa});
}

/// Five different runs: pressures, gases, stiff and not.
std::vector<MuscleModel> five_muscles() {
  return {muscle(236.63e3, 2.0), muscle(138e3, 0.0), muscle(207e3, 0.02), muscle(300e3, 5.0), muscle(180e3, 1.0)};
}

/// The batch's entries of run r against `run`: every kept channel at every kept row, the
/// extremes over every sample, the counters; all bit for bit.
void check_run(const BatchResult& batch, std::size_t r, const SimulationResult& run) {
  INFO("run " << r);
  CHECK(batch.errors[r].empty());
  for (std::size_t c = 0; c < batch.channels.size(); ++c) {
    const std::string& name = batch.channels[c];
    INFO("channel " << name);
    const std::vector<double>* column = nullptr;
    SimulationResult::for_each_column(
        [&](const char* column_name, std::vector<double> SimulationResult::*member, const char*, const char*, bool) {
          if (name == column_name) column = &(run.*member);
        });
    REQUIRE(column != nullptr);
    for (std::size_t k = 0; k < batch.rows.size(); ++k) {
      CHECK(batch.values[c][r * batch.rows.size() + k] == (*column)[batch.rows[k]]);
    }
    CHECK(batch.maximum[c][r] == *std::max_element(column->begin(), column->end()));
    CHECK(batch.minimum[c][r] == *std::min_element(column->begin(), column->end()));
  }
  SolverStatistics::for_each_counter([&](const char* counter, long SolverStatistics::*member, const char*) {
    INFO(counter);
    CHECK(batch.statistics[r].*member == run.statistics.*member);
  });
  CHECK(batch.statistics[r].method == run.statistics.method);
}

BatchRequest request(std::vector<std::size_t> rows, std::size_t threads,
                     std::vector<std::string> channels = {"force_N", "gauge_pressure_Pa", "temperature_K", "work_J"}) {
  BatchRequest out;
  out.channels = std::move(channels);
  out.rows = std::move(rows);
  out.threads = threads;
  return out;
}

/// Every array of two results equal, NaN where NaN.
void check_same(const BatchResult& a, const BatchResult& b) {
  const auto same = [](const std::vector<double>& x, const std::vector<double>& y) {
    return std::equal(x.begin(), x.end(), y.begin(), y.end(),
                      [](double u, double v) { return u == v || (std::isnan(u) && std::isnan(v)); });
  };
  REQUIRE(a.runs == b.runs);
  for (std::size_t c = 0; c < a.channels.size(); ++c) {
    CHECK(same(a.values[c], b.values[c]));
    CHECK(same(a.maximum[c], b.maximum[c]));
    CHECK(same(a.minimum[c], b.minimum[c]));
  }
  CHECK(a.errors == b.errors);
  CHECK(a.failures == b.failures);
  for (std::size_t r = 0; r < a.runs; ++r) CHECK(a.statistics[r].steps == b.statistics[r].steps);
}

}  // namespace

TEST_CASE("run_batch: each run is Simulator::run's, bit for bit, by every method", "[sim][batch]") {
  const auto method = GENERATE(IntegrationMethod::bdf, IntegrationMethod::dopri5, IntegrationMethod::rosenbrock4,
                               IntegrationMethod::automatic);
  INFO(method);
  SimulatorConfig config;
  config.method = method;
  const Simulator simulator(config);
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 2);
  const std::vector<MuscleModel> models = five_muscles();
  const BatchResult batch = simulator.run_batch(models, trajectory, request({0, 3, 150, 320, 640}, 2));
  REQUIRE(batch.runs == models.size());
  CHECK(batch.channels == std::vector<std::string>{"force_N", "gauge_pressure_Pa", "temperature_K", "work_J"});
  for (std::size_t r = 0; r < models.size(); ++r) check_run(batch, r, simulator.run(models[r], trajectory));
  // The runs differ: equal entries are not a property of the inputs.
  CHECK(batch.maximum[0][0] != batch.maximum[0][1]);
}

TEST_CASE("run_batch: the number of threads changes no number", "[sim][batch][threads]") {
  const Simulator simulator;
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 2);
  std::vector<MuscleModel> models;
  for (int i = 0; i < 12; ++i) models.push_back(muscle(120e3 + 15e3 * i, i % 3 == 0 ? 0.0 : 0.5 + i));
  std::vector<std::size_t> rows(trajectory.size());
  for (std::size_t k = 0; k < rows.size(); ++k) rows[k] = k;
  const BatchResult one = simulator.run_batch(models, trajectory, request(rows, 1));
  for (const std::size_t threads : {std::size_t{2}, std::size_t{5}, std::size_t{40}, std::size_t{0}}) {
    INFO(threads << " threads");
    check_same(simulator.run_batch(models, trajectory, request(rows, threads)), one);
  }
}

TEST_CASE("run_batch: a run the model cannot follow fails alone, with its message", "[sim][batch]") {
  // PAM 2's fibres are 0.258 m long: a muscle mounted at 0.24 m and stretched 4 cm more leaves
  // the braid's range.
  const Simulator simulator;
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 1);
  const std::vector<MuscleModel> models{muscle(200e3, 2.0), muscle(200e3, 2.0, 0.24), muscle(150e3, 0.0)};
  const BatchResult batch = simulator.run_batch(models, trajectory, request({0, 100}, 3));
  CHECK(batch.errors[0].empty());
  CHECK_THAT(batch.errors[1], Catch::Contains("outside the braid's range"));
  CHECK(batch.failures == std::vector<RunFailure>{RunFailure::none, RunFailure::input, RunFailure::none});
  for (std::size_t c = 0; c < batch.channels.size(); ++c) {
    CHECK(std::isnan(batch.maximum[c][1]));
    CHECK(std::isnan(batch.values[c][1 * 2 + 0]));
  }
  CHECK(batch.statistics[1].steps == 0);
  check_run(batch, 0, simulator.run(models[0], trajectory));
  check_run(batch, 2, simulator.run(models[2], trajectory));
}

TEST_CASE("run_batch: a shape table and moved motions serve the runs as they serve one run", "[sim][batch]") {
  const Simulator simulator;
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 1);
  const std::vector<MuscleModel> models{muscle(200e3, 2.0), muscle(150e3, 2.0)};
  const ShapeTable shapes(models[0].params().build, 0.167, trajectory);
  const BatchResult tabulated = simulator.run_batch(models, trajectory, request({5, 60}, 2), &shapes);
  for (std::size_t r = 0; r < models.size(); ++r) {
    CHECK(tabulated.statistics[r].tabulated_shapes == static_cast<long>(trajectory.size()));
    check_run(tabulated, r, simulator.run(models[r], trajectory, &shapes));
  }
  // Run 1 follows the crosshead's motion less 1 mm of slack.
  std::vector<double> slackened = trajectory.elongation();
  for (double& e : slackened) e = std::max(0.0, e - 1e-3);
  const std::vector<ElongationTrajectory> motions{trajectory, ElongationTrajectory(trajectory.time(), slackened)};
  const BatchResult moved = simulator.run_batch(models, trajectory, request({5, 60}, 2), nullptr, motions);
  check_run(moved, 0, simulator.run(models[0], trajectory));
  check_run(moved, 1, simulator.run(models[1], motions[1]));
}

TEST_CASE("run_batch: refuses unknown channels, rows out of order and motions that do not fit", "[sim][batch]") {
  const Simulator simulator;
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 1);
  const std::vector<MuscleModel> models{muscle(200e3, 2.0)};
  CHECK_THROWS_WITH(simulator.run_batch(models, trajectory, request({}, 1, {"force_N", "torque_Nm"})),
                    Catch::Contains("unknown channel 'torque_Nm'") && Catch::Contains("gauge_pressure_Pa"));
  CHECK_THROWS_WITH(simulator.run_batch(models, trajectory, request({}, 1, {"time_s"})),
                    Catch::Contains("unknown channel 'time_s'"));
  CHECK_THROWS_WITH(simulator.run_batch(models, trajectory, request({}, 1, {"force_N", "force_N"})),
                    Catch::Contains("'force_N' is asked for twice"));
  CHECK_THROWS_WITH(simulator.run_batch(models, trajectory, request({4, 4}, 1)),
                    Catch::Contains("rows[1] = 4 does not increase"));
  CHECK_THROWS_WITH(simulator.run_batch(models, trajectory, request({trajectory.size()}, 1)),
                    Catch::Contains("past the trajectory's last sample"));
  CHECK_THROWS_WITH(simulator.run_batch(models, trajectory, request({}, 1), nullptr, {trajectory, trajectory}),
                    Catch::Contains("2 motions for 1 models"));
  const ElongationTrajectory other({0.0, 1.0}, {0.0, 0.01});
  CHECK_THROWS_WITH(simulator.run_batch(models, trajectory, request({}, 1), nullptr, {other}),
                    Catch::Contains("motion 0 is not sampled at the trajectory's times"));
  // No runs: an empty result, no thread started.
  CHECK(simulator.run_batch(std::vector<MuscleModel>{}, trajectory, request({0}, 4)).runs == 0);
}

TEST_CASE("ParameterSets: each run's muscle is the one a caller makes by hand", "[sim][batch]") {
  MuscleParams base;
  base.gas.process = GasProcess::heat_transfer;
  base.gas.heat_transfer_time_constant_s = 2.0;
  const InitialState start{0.167, 207e3};
  const std::vector<std::string> names{"initial.gauge_pressure_Pa", "build.braid_angle_deg",
                                       "friction.sharpness_s_per_m", "gas.ambient_temperature_K",
                                       "bladder.shear_modulus_Pa"};
  const ParameterSets sets(base, start, false, names,
                           {150e3, 30.0, 5.0,  290.0, 1e6,    //
                            250e3, 33.0, 1.0,  300.0, 2e6,    //
                            200e3, 95.0, 1.0,  296.0, 1e6,    // no braid is wound at 95 deg
                            200e3, 31.0, -1.0, 296.0, 1e6});  // a negative friction sharpness
  REQUIRE(sets.runs() == 4);

  MuscleParams by_hand = base;
  by_hand.friction.sharpness_s_per_m = 5.0;
  by_hand.gas.ambient_temperature_K = 290.0;
  by_hand.bladder = BladderLaw::neo_hookean(1e6);
  by_hand.build.fiber_revolutions = fiber_revolutions_for_braid_angle(by_hand.build, 30.0);
  const auto [params, initial] = sets.at(0);
  CHECK(params.build.fiber_revolutions == by_hand.build.fiber_revolutions);
  CHECK(params.friction.sharpness_s_per_m == 5.0);
  CHECK(params.gas.ambient_temperature_K == 290.0);
  CHECK(params.bladder.form == BladderLaw::Form::neo_hookean);
  CHECK(params.bladder.shear_modulus_Pa == 1e6);
  CHECK(initial.gauge_pressure_Pa == 150e3);
  CHECK(initial.length_m == 0.167);
  CHECK_THROWS_AS(sets.at(2), InvalidParameter);
  CHECK_THROWS_AS(sets.at(3), InvalidParameter);
  CHECK_THROWS_AS(sets.at(4), std::out_of_range);

  const Simulator simulator;
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 1);
  const BatchResult batch = simulator.run_batch(sets, trajectory, request({0, 50, 200}, 3));
  check_run(batch, 0, simulator.run(MuscleModel(by_hand, InitialState{0.167, 150e3}), trajectory));
  const auto [second, second_start] = sets.at(1);
  check_run(batch, 1, simulator.run(MuscleModel(second, second_start), trajectory));
  CHECK_THAT(batch.errors[2], Catch::Contains("braid_angle_deg = 95"));
  CHECK_THAT(batch.errors[3], Catch::Contains("sharpness_s_per_m"));
  CHECK(batch.failures ==
        std::vector<RunFailure>{RunFailure::none, RunFailure::none, RunFailure::parameters, RunFailure::parameters});
}

TEST_CASE("ParameterSets: a sealed start inflated freely to each run's pressure", "[sim][batch]") {
  const MuscleParams base;
  const ParameterSets sets(base, InitialState{}, true, {"initial.gauge_pressure_Pa"}, {100e3, 300e3});
  for (std::size_t r = 0; r < 2; ++r) {
    const auto [params, start] = sets.at(r);
    const InitialState inflated = inflated_and_sealed(params, r == 0 ? 100e3 : 300e3);
    CHECK(start.length_m == inflated.length_m);
    CHECK(start.gauge_pressure_Pa == inflated.gauge_pressure_Pa);
  }
  // A run that sets its length starts there instead.
  const ParameterSets mounted(base, InitialState{}, true, {"initial.gauge_pressure_Pa", "initial.length_m"},
                              {100e3, 0.17});
  CHECK(mounted.at(0).second.length_m == 0.17);
}

TEST_CASE("ParameterSets: refuses unknown, repeated and contradicting names", "[sim][batch]") {
  const MuscleParams base;
  const InitialState start;
  CHECK_THROWS_WITH(ParameterSets(base, start, false, {"build.colour"}, {1.0}),
                    Catch::Contains("'build.colour' is not a field a run can set"));
  CHECK_THROWS_WITH(ParameterSets(base, start, false, {"build.construction"}, {1.0}), Catch::Contains("numbers only"));
  CHECK_THROWS_WITH(
      ParameterSets(base, start, false, {"gas.ambient_temperature_K", "gas.ambient_temperature_K"}, {290.0, 300.0}),
      Catch::Contains("named twice"));
  CHECK_THROWS_WITH(
      ParameterSets(base, start, false, {"build.braid_angle_deg", "build.fiber_revolutions"}, {30.0, 2.0}),
      Catch::Contains("say the same"));
  CHECK_THROWS_WITH(
      ParameterSets(base, start, false, {"initial.length_m", "initial.gauge_pressure_Pa"}, {0.2, 1e5, 0.3}),
      Catch::Contains("3 values are not a whole number of runs of 2 fields"));
  CHECK_THROWS_AS(ParameterSets(base, start, false, {}, {}), InvalidInput);
}
