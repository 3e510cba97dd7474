// The simulator as a piece of software: re-entrant across threads, its solver statistics, the
// model's warm-started evaluation and the output path.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <thread>
#include <utility>
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
  CHECK(a.gauge_pressure_Pa == b.gauge_pressure_Pa);
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
  // With compliant fibers the warm fiber length is a chord Newton iteration from the last
  // solve's, the cold one a bracketing search: they stop within 1e-14 of each other, and the
  // rates, through the fibers' rate of length, agree to what that difference moves them by.
  MuscleParams plain;
  plain.gas.process = GasProcess::heat_transfer;
  MuscleParams extended = plain;
  extended.extensions.fiber_compliance_per_N = 1e-2;  // the fibers' balance calls the geometry too
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
      CHECK_REL(warm.fiber_length_m, cold.fiber_length_m, 1e-14);
      const double rate_tolerance = params.extensions.fiber_compliance_per_N > 0.0 ? 1e-10 : 1e-12;
      for (int i = 0; i < State::size; ++i) {
        INFO("rate " << i);
        CHECK(std::abs(warm.rate[i] - cold.rate[i]) <= rate_tolerance * std::abs(cold.rate[i]) + 1e-300);
      }
      CHECK(std::isnan(warm.shape.braid_angle));
      CHECK(!std::isnan(cold.shape.braid_angle));
    }
  }
}

namespace {

/// The same piecewise-linear path as `coarse`, every segment sampled `per_segment` times.
ElongationTrajectory refined(const ElongationTrajectory& coarse, int per_segment) {
  std::vector<double> time;
  std::vector<double> elongation;
  for (std::size_t k = 0; k + 1 < coarse.size(); ++k) {
    for (int i = 0; i < per_segment; ++i) {
      const double f = static_cast<double>(i) / per_segment;
      time.push_back(coarse.time()[k] + f * (coarse.time()[k + 1] - coarse.time()[k]));
      elongation.push_back(coarse.elongation()[k] + f * (coarse.elongation()[k + 1] - coarse.elongation()[k]));
    }
  }
  time.push_back(coarse.time().back());
  elongation.push_back(coarse.elongation().back());
  return ElongationTrajectory(time, elongation);
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& reference, std::size_t stride) {
  double difference = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) difference = std::max(difference, std::abs(a[k] - reference[k * stride]));
  return difference;
}

double largest_magnitude(const std::vector<double>& values) {
  double largest = 0.0;
  for (double v : values) largest = std::max(largest, std::abs(v));
  return largest;
}

SimulatorConfig tolerance(double rtol) {
  SimulatorConfig config;
  config.relative_tolerance = rtol;
  config.absolute_tolerance_K = rtol;
  config.absolute_tolerance_J = rtol;
  return config;
}

}  // namespace

TEST_CASE("Simulator: samples read off CVODES's steps agree with a dense reference to the tolerance", "[sim][output]") {
  // Every sample is interpolated from the step that passed it (CVodeGetDky). Against the same
  // run at rtol 1e-12, force, pressure and temperature must agree to 10 x rtol of each trace's
  // largest value: BDF's global error is a small multiple of the local tolerance it controls
  // (3.5 x on the thesis's 10-cycle test, with a CVode call per sample and with one per step).
  MuscleParams params;
  params.gas.process = GasProcess::heat_transfer;
  params.gas.heat_transfer_time_constant_s = 2.0;
  const MuscleModel model(params, InitialState{0.167, 236.63e3});
  const ElongationTrajectory trajectory = thesis_protocol(0.05, 2.5e-3, 3, 0.1, 1.0);
  const double rtol = 1e-8;
  const SimulationResult run = Simulator(tolerance(rtol)).run(model, trajectory);
  const SimulationResult reference = Simulator(tolerance(1e-12)).run(model, trajectory);
  REQUIRE(run.time_s == trajectory.time());
  CHECK(run.statistics.output_evaluations == static_cast<long>(trajectory.size()));
  const std::pair<const char*, std::vector<double> SimulationResult::*> traces[] = {
      {"force_N", &SimulationResult::force_N},
      {"gauge_pressure_Pa", &SimulationResult::gauge_pressure_Pa},
      {"temperature_K", &SimulationResult::temperature_K}};
  for (const auto& [name, trace] : traces) {
    const double error = largest_difference(run.*trace, reference.*trace, 1) / largest_magnitude(reference.*trace);
    INFO(name << ": largest difference / largest value = " << error);
    CHECK(error <= 10.0 * rtol);
  }
}

TEST_CASE("Simulator: the samples do not steer the steps", "[sim][output]") {
  // One CVODES step per call, from corner to corner: sampling the same path four times as
  // densely must leave the steps alone and the shared samples equal to what rounding in the
  // lengths (e_k + v (t - t_k) summed differently) lets through CVODES's Newton iteration, whose
  // convergence test stops at 0.1 of the error tolerance: 0.1 x rtol of each trace's scale.
  MuscleParams heat;
  heat.gas.process = GasProcess::heat_transfer;
  heat.gas.heat_transfer_time_constant_s = 2.0;
  // The explicit method reads each sample off its dense output too, but its max-norm error test
  // can turn on rounding: a step accepted on one path is rejected on the other (measured: one
  // step more in 25 and in 184, the channels then 3.5 x rtol apart). It is held to the steps
  // give or take two, and to the 10 x rtol its accuracy is held to below.
  const auto method = GENERATE(IntegrationMethod::bdf, IntegrationMethod::dopri5, IntegrationMethod::rosenbrock4);
  INFO(method);
  const bool cvodes = method == IntegrationMethod::bdf;
  for (const MuscleParams& params : {MuscleParams{}, heat}) {
    INFO("process " << static_cast<int>(params.gas.process));
    const MuscleModel model(params, InitialState{0.167, 236.63e3});
    const ElongationTrajectory coarse = thesis_protocol(0.05, 2.5e-3, 3, 0.1, 1.0);
    SimulatorConfig config;
    config.method = method;
    const SimulationResult a = Simulator(config).run(model, coarse);
    const SimulationResult b = Simulator(config).run(model, refined(coarse, 4));
    if (cvodes) {
      CHECK(b.statistics.steps == a.statistics.steps);
      CHECK(b.statistics.rhs_evaluations == a.statistics.rhs_evaluations);
    } else {
      CHECK(std::abs(b.statistics.steps - a.statistics.steps) <= 2);
    }
    CHECK(b.statistics.restarts == a.statistics.restarts);
    CHECK(b.statistics.output_evaluations == 4 * (a.statistics.output_evaluations - 1) + 1);
    CHECK(largest_difference(a.time_s, b.time_s, 4) <= 1e-12);
    for (auto trace : {&SimulationResult::force_N, &SimulationResult::gauge_pressure_Pa,
                       &SimulationResult::temperature_K, &SimulationResult::gas_volume_m3}) {
      const double bound = (cvodes ? 0.1 : 10.0) * config.relative_tolerance;
      CHECK(largest_difference(a.*trace, b.*trace, 4) <= bound * largest_magnitude(a.*trace));
    }
  }
}

TEST_CASE("Simulator: more steps than max_steps between two samples is an error", "[sim][output]") {
  // One segment of 20 s with a gas that exchanges heat in 0.02 s: hundreds of steps, no sample
  // between them. CVODES, called one step at a time, cannot count them; the simulator does.
  MuscleParams params;
  params.gas.process = GasProcess::heat_transfer;
  params.gas.heat_transfer_time_constant_s = 0.02;
  const MuscleModel model(params, InitialState{0.167, 236.63e3});
  const ElongationTrajectory ramp({0.0, 20.0}, {0.0, 0.05});
  SimulatorConfig config;
  const SimulationResult unlimited = Simulator(config).run(model, ramp);
  REQUIRE(unlimited.statistics.steps > 20);
  config.max_steps = 20;
  CHECK_THROWS_AS(Simulator(config).run(model, ramp), SolverError);
  CHECK_THROWS_WITH(Simulator(config).run(model, ramp),
                    Catch::Contains("CV_TOO_MUCH_WORK") && Catch::Contains("SimulatorConfig.max_steps"));
  // The explicit method counts its own steps: on this stiff gas it needs hundreds too.
  config.method = IntegrationMethod::dopri5;
  CHECK_THROWS_WITH(Simulator(config).run(model, ramp),
                    Catch::Contains("dopri5 took more than 20 steps") && Catch::Contains("SimulatorConfig.max_steps"));
}

namespace {

/// The sealed muscle of table C.2 whose gas exchanges heat with the wall in `tau_s`.
MuscleModel heat_exchanging(double tau_s) {
  MuscleParams params;
  params.gas.process = GasProcess::heat_transfer;
  params.gas.heat_transfer_time_constant_s = tau_s;
  return MuscleModel(params, InitialState{0.167, 236.63e3});
}

SimulatorConfig with_method(SimulatorConfig config, IntegrationMethod method) {
  config.method = method;
  return config;
}

}  // namespace

TEST_CASE("MuscleModel::fastest_rate_per_s: the rates at which states relax on their own", "[sim][stiffness]") {
  // Each rate is the magnitude of the state's own term in its equation (model.hxx):
  // dT/dt = -(T - T_amb) / tau + ..., dm/dt = -leak (m - p_atm V / (R T)), ds/dt = -s / tau_v + ...
  const InitialState initial{0.167, 236.63e3};
  CHECK(MuscleModel(MuscleParams{}, initial).fastest_rate_per_s() == 0.0);  // polytropic, sealed
  CHECK(heat_exchanging(0.02).fastest_rate_per_s() == Approx(50.0).epsilon(1e-15));
  CHECK(heat_exchanging(0.0).fastest_rate_per_s() == 0.0);  // instant exchange: isothermal, no state relaxes
  MuscleParams leaking;
  leaking.extensions.leak_rate_per_s = 3.0;
  CHECK(MuscleModel(leaking, initial).fastest_rate_per_s() == 3.0);
  MuscleParams viscous;
  viscous.extensions.viscoelastic_time_constant_s = 0.01;
  CHECK(MuscleModel(viscous, initial).fastest_rate_per_s() == 0.0);  // no strength: the stresses stay zero
  viscous.extensions.viscoelastic_strength = 0.5;
  CHECK(MuscleModel(viscous, initial).fastest_rate_per_s() == Approx(100.0).epsilon(1e-15));
}

TEST_CASE("Simulator: rosenbrock4 holds the states whose rates are zero wherever a run goes", "[sim][stiffness]") {
  // rosenbrock4 integrates only the states that move (and the energies): the temperature unless
  // the gas is isothermal, the gas mass through a leak, the viscous stresses with a strength.
  // Its premise, on the model: the others' rates are exactly zero at any length, rate and
  // temperature a run can reach.
  const InitialState initial{0.167, 236.63e3};
  MuscleParams isothermal;  // polytropic, n = 1
  MuscleParams instant;
  instant.gas.process = GasProcess::heat_transfer;
  instant.gas.heat_transfer_time_constant_s = 0.0;
  for (const MuscleParams& params : {isothermal, instant}) {
    const MuscleModel model(params, initial);
    for (const double length : {0.168, 0.19, 0.21}) {
      for (const double velocity : {-5e-3, 0.0, 2.5e-3}) {
        State state = model.initial();
        state[State::temperature_K] = 310.0;
        const State rate = model.evaluate(length, velocity, state).rate;
        CHECK(rate[State::temperature_K] == 0.0);
        CHECK(rate[State::gas_mass_kg] == 0.0);
        CHECK(rate[State::viscous_stress_l_Pa] == 0.0);
        CHECK(rate[State::viscous_stress_h_Pa] == 0.0);
        if (velocity != 0.0) CHECK(rate[State::work_J] != 0.0);  // the energies move: they are integrated
      }
    }
  }
  // A run holds them bit for bit, and moves those that do move.
  SimulatorConfig config;
  config.method = IntegrationMethod::rosenbrock4;
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 1);
  const SimulationResult held = Simulator(config).run(MuscleModel(isothermal, initial), trajectory);
  const MuscleModel isothermal_model(isothermal, initial);
  for (std::size_t k = 0; k < held.time_s.size(); ++k) {
    CHECK(held.temperature_K[k] == isothermal_model.initial_temperature());
    CHECK(held.gas_mass_kg[k] == isothermal_model.gas_mass());
  }
  MuscleParams leaking = isothermal;
  leaking.extensions.leak_rate_per_s = 0.05;
  leaking.extensions.viscoelastic_strength = 0.5;
  const SimulationResult moving = Simulator(config).run(MuscleModel(leaking, initial), trajectory);
  CHECK(moving.gas_mass_kg.back() < 0.99 * moving.gas_mass_kg.front());
  const SimulationResult reference = Simulator(tolerance(1e-12)).run(MuscleModel(leaking, initial), trajectory);
  CHECK(largest_difference(moving.force_N, reference.force_N, 1) <=
        10.0 * config.relative_tolerance * largest_magnitude(reference.force_N));
  // Every step factorises its matrix once; a rejected one too.
  CHECK(moving.statistics.linear_solver_setups == moving.statistics.jacobian_evaluations);
  CHECK(moving.statistics.jacobian_evaluations == moving.statistics.steps + moving.statistics.error_test_failures);
}

TEST_CASE("Simulator: BDF, Adams and Dormand-Prince agree to the tolerance on a stiff and a non-stiff run",
          "[sim][stiffness]") {
  // Each method against the same run by BDF at rtol 1e-12: force, pressure and temperature
  // within 10 x rtol of each trace's largest value, the bound the dense-reference test above
  // holds BDF to (its global error a small multiple of the local tolerance it controls), on a
  // gas that exchanges heat in 5 s (non-stiff) and in 0.02 s (stiff: Adams pays in steps).
  const ElongationTrajectory trajectory = thesis_protocol(0.05, 2.5e-3, 3, 0.1, 1.0);
  const double rtol = 1e-8;
  for (double tau : {5.0, 0.02}) {
    const MuscleModel model = heat_exchanging(tau);
    const SimulationResult reference = Simulator(tolerance(1e-12)).run(model, trajectory);
    if (tau < 1.0) {
      // Stiff: the explicit method's steps shrink to the heat exchange's time scale, the
      // linearly implicit one's do not. (With Boost 1.74's own d4 rosenbrock4 lost its order on
      // this time-dependent motion and took several times dopri5's steps instead.)
      const long explicit_steps =
          Simulator(with_method(tolerance(rtol), IntegrationMethod::dopri5)).run(model, trajectory).statistics.steps;
      const long rosenbrock_steps = Simulator(with_method(tolerance(rtol), IntegrationMethod::rosenbrock4))
                                        .run(model, trajectory)
                                        .statistics.steps;
      CHECK(rosenbrock_steps < explicit_steps / 2);
    }
    for (IntegrationMethod method : {IntegrationMethod::bdf, IntegrationMethod::adams, IntegrationMethod::dopri5,
                                     IntegrationMethod::rosenbrock4}) {
      const SimulationResult run = Simulator(with_method(tolerance(rtol), method)).run(model, trajectory);
      CHECK(run.statistics.method == method);
      for (auto trace :
           {&SimulationResult::force_N, &SimulationResult::gauge_pressure_Pa, &SimulationResult::temperature_K}) {
        const double error = largest_difference(run.*trace, reference.*trace, 1) / largest_magnitude(reference.*trace);
        INFO("tau = " << tau << " s, " << method << ": largest difference / largest value = " << error);
        CHECK(error <= 10.0 * rtol);
      }
    }
  }
}

TEST_CASE("Simulator: auto runs Dormand-Prince on a non-stiff run, Rosenbrock or BDF on a stiff one",
          "[sim][stiffness]") {
  // The thesis's 10-cycle protocol: ramps of 0.0523 m / 2.5 mm/s = 20.9 s between corners, so
  // the step the tolerance allows is 20.9 s x rtol^(1/6) = 0.97 s at rtol 1e-8. A gas exchanging
  // heat in 5 s relaxes at 0.2 /s (ratio 0.19: dopri5); in 0.02 s at 50 /s (ratio 48: stiff, so
  // rosenbrock4 at 1e-8 and BDF below kRosenbrockTightestTolerance).
  const ElongationTrajectory trajectory = thesis_protocol(0.0523);
  const SimulatorConfig automatic = with_method(tolerance(1e-8), IntegrationMethod::automatic);
  const StiffnessEstimate slow = estimate_stiffness(heat_exchanging(5.0), trajectory, automatic);
  CHECK(slow.longest_piece_s == Approx(20.92).epsilon(1e-12));
  CHECK(slow.expected_step_s == Approx(20.92 * std::pow(1e-8, 1.0 / 6.0)).epsilon(1e-12));
  CHECK(slow.ratio() == Approx(0.2 * slow.expected_step_s).epsilon(1e-12));
  CHECK_FALSE(slow.stiff());
  CHECK(estimate_stiffness(heat_exchanging(0.02), trajectory, automatic).stiff());
  // A step limit below 1 / rate makes the fast gas non-stiff too: the steps cannot grow past it.
  SimulatorConfig limited = automatic;
  limited.max_step_s = 0.01;
  CHECK_FALSE(estimate_stiffness(heat_exchanging(0.02), trajectory, limited).stiff());

  struct Pick {
    double tau_s;
    double rtol;
    IntegrationMethod expected;
  };
  for (const Pick pick : {Pick{5.0, 1e-8, IntegrationMethod::dopri5}, Pick{0.02, 1e-8, IntegrationMethod::rosenbrock4},
                          Pick{0.02, 1e-10, IntegrationMethod::bdf}}) {
    const auto [tau, rtol, expected] = pick;
    const MuscleModel model = heat_exchanging(tau);
    const SimulatorConfig config = with_method(tolerance(rtol), IntegrationMethod::automatic);
    const SimulationResult chosen = Simulator(config).run(model, trajectory);
    INFO("tau = " << tau << " s, rtol " << rtol);
    CHECK(chosen.statistics.method == expected);
    // The same solver as asking for the method by name: the same numbers, bit for bit.
    const SimulationResult named = Simulator(with_method(config, expected)).run(model, trajectory);
    CHECK(chosen.force_N == named.force_N);
    CHECK(chosen.statistics.steps == named.statistics.steps);
  }
}

TEST_CASE("Simulator: run_blocks hands run's samples over in blocks, bit for bit", "[sim][blocks]") {
  const Case c = four_cases()[1];  // heat transfer, holds: corners (restarts) fall inside blocks
  const MuscleModel model(c.params, c.initial);
  const auto method = GENERATE(IntegrationMethod::bdf, IntegrationMethod::dopri5, IntegrationMethod::rosenbrock4);
  INFO(method);
  const Simulator simulator(with_method(SimulatorConfig{}, method));
  const SimulationResult whole = simulator.run(model, c.trajectory);
  const std::size_t n = c.trajectory.size();
  for (const std::size_t block_size : {std::size_t{1}, std::size_t{7}, std::size_t{500}, n, n + 3}) {
    INFO("blocks of " << block_size);
    SimulationResult joined;
    std::size_t calls = 0;
    const auto append = [&](std::size_t first, const SimulationResult& block) {
      CHECK(first == joined.time_s.size());  // in order, none skipped or repeated
      CHECK(block.time_s.size() == std::min(block_size, n - first));
      const auto add = [](std::vector<double>& to, const std::vector<double>& from) {
        to.insert(to.end(), from.begin(), from.end());
      };
      add(joined.time_s, block.time_s);
      add(joined.length_m, block.length_m);
      add(joined.force_N, block.force_N);
      add(joined.friction_force_N, block.friction_force_N);
      add(joined.gauge_pressure_Pa, block.gauge_pressure_Pa);
      add(joined.temperature_K, block.temperature_K);
      add(joined.gas_volume_m3, block.gas_volume_m3);
      add(joined.work_J, block.work_J);
      add(joined.heat_lost_J, block.heat_lost_J);
      add(joined.friction_dissipated_J, block.friction_dissipated_J);
      ++calls;
    };
    joined.statistics = simulator.run_blocks(model, c.trajectory, block_size, append);
    CHECK(calls == (n + block_size - 1) / block_size);
    check_identical(joined, whole);
    CHECK(joined.statistics.output_evaluations == static_cast<long>(n));
    CHECK(joined.statistics.restarts == whole.statistics.restarts);
  }
  CHECK_THROWS_AS(simulator.run_blocks(model, c.trajectory, 0, [](std::size_t, const SimulationResult&) {}),
                  InvalidInput);
  // A sink that fails (a full disk) stops the run there; the blocks before it were handed over.
  std::size_t seen = 0;
  CHECK_THROWS_WITH(simulator.run_blocks(model, c.trajectory, 10,
                                         [&seen](std::size_t, const SimulationResult&) {
                                           if (++seen == 3) throw std::runtime_error("disk full");
                                         }),
                    "disk full");
  CHECK(seen == 3);
}
