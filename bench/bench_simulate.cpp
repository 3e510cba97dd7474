// pamkit_bench_simulate: times one simulation of a thesis test and one right-hand-side
// evaluation in C++, without Python, cold (MuscleModel::evaluate) and as the simulator makes it
// (MuscleModel::evaluate_with, warm-started), and prints one JSON object.
// bench/bench_simulate.py runs it beside the Python bindings to measure their overhead and
// to see how much of the wall time is model evaluations. See bench/README.md.
//
// With --integrator dopri5 it times instead the same test integrated by an explicit Runge-Kutta
// method with dense output on the same right-hand side (Boost.Odeint's Dormand-Prince 5(4)):
// the yardstick for what CVODES's own bookkeeping costs, printed with its channels so the
// caller can compare its accuracy.
//
// Usage: pamkit_bench_simulate [--name value]...   (every option and its default in Options)

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "dopri5_reference.hpp"
#include "pamkit/sim/simulator.hpp"

namespace {

/// The test to time; defaults are the 10-cycle test of table C.2 (207 kPa, 90 %).
struct Options {
  double length_m = 0.167;                ///< InitialState.length_m [m]
  double gauge_pressure_Pa = 236.63e3;    ///< InitialState.gauge_pressure_Pa [Pa]
  double max_elongation_m = 0.0523;       ///< thesis_protocol max elongation [m]
  double speed_m_per_s = 2.5e-3;          ///< thesis_protocol speed [m/s]
  int cycles = 10;                        ///< thesis_protocol cycles [1]
  double sample_period_s = 0.1;           ///< thesis_protocol sample period [s]
  std::string process = "heat_transfer";  ///< GasProcess: heat_transfer or polytropic
  double tau_s = 5.0;                     ///< GasParams.heat_transfer_time_constant_s [s]
  double polytropic_index = 1.0;          ///< GasParams.polytropic_index [1]
  double sharpness_s_per_m = 1.0;         ///< FrictionParams.sharpness_s_per_m [s/m]
  double rtol = 1e-8;                     ///< SimulatorConfig.relative_tolerance [1]
  double atol_K = 1e-8;                   ///< SimulatorConfig.absolute_tolerance_K [K]
  double atol_J = 1e-8;                   ///< SimulatorConfig.absolute_tolerance_J [J]
  std::string method = "bdf";             ///< SimulatorConfig.method: bdf, adams, dopri5, rosenbrock4 or auto
  std::string integrator = "pamkit";      ///< pamkit (Simulator::run) or dopri5 (Boost.Odeint, same RHS)
  int repeats = 7;                        ///< timed simulations; the best is reported
  long evaluations = 200000;              ///< evaluate() calls per timed batch
  int evaluation_batches = 7;             ///< timed batches; the best is reported
};

double number(const char* name, const char* text) {
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0') throw std::invalid_argument(std::string("--") + name + ": not a number: " + text);
  return value;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    if (key == "--help" || key == "-h") {
      std::puts(
          "pamkit_bench_simulate [--length L] [--gauge P] [--max-elongation E] [--speed V] [--cycles N]\n"
          "  [--sample-period S] [--process heat_transfer|polytropic] [--tau T] [--polytropic-index N]\n"
          "  [--sharpness K] [--rtol R] [--atol-K A] [--atol-J A] [--method bdf|adams|dopri5|rosenbrock4|auto]\n"
          "  [--integrator pamkit|dopri5] [--repeats N] [--evaluations N]"
          " [--evaluation-batches N]\nPrints one JSON object; times in seconds.");
      std::exit(0);
    }
    if (key.rfind("--", 0) != 0 || i + 1 >= argc) throw std::invalid_argument("bad argument: " + key);
    const std::string name = key.substr(2);
    const char* value = argv[++i];
    if (name == "length") o.length_m = number("length", value);
    else if (name == "gauge") o.gauge_pressure_Pa = number("gauge", value);
    else if (name == "max-elongation") o.max_elongation_m = number("max-elongation", value);
    else if (name == "speed") o.speed_m_per_s = number("speed", value);
    else if (name == "cycles") o.cycles = static_cast<int>(number("cycles", value));
    else if (name == "sample-period") o.sample_period_s = number("sample-period", value);
    else if (name == "process") o.process = value;
    else if (name == "tau") o.tau_s = number("tau", value);
    else if (name == "polytropic-index") o.polytropic_index = number("polytropic-index", value);
    else if (name == "sharpness") o.sharpness_s_per_m = number("sharpness", value);
    else if (name == "rtol") o.rtol = number("rtol", value);
    else if (name == "atol-K") o.atol_K = number("atol-K", value);
    else if (name == "atol-J") o.atol_J = number("atol-J", value);
    else if (name == "method") o.method = value;
    else if (name == "integrator") o.integrator = value;
    else if (name == "repeats") o.repeats = static_cast<int>(number("repeats", value));
    else if (name == "evaluations") o.evaluations = static_cast<long>(number("evaluations", value));
    else if (name == "evaluation-batches") o.evaluation_batches = static_cast<int>(number("evaluation-batches", value));
    else throw std::invalid_argument("unknown option: " + key);
  }
  if (o.process != "heat_transfer" && o.process != "polytropic") {
    throw std::invalid_argument("--process must be heat_transfer or polytropic, got " + o.process);
  }
  if (o.method != "bdf" && o.method != "adams" && o.method != "dopri5" && o.method != "rosenbrock4" &&
      o.method != "auto") {
    throw std::invalid_argument("--method must be bdf, adams, dopri5, rosenbrock4 or auto, got " + o.method);
  }
  if (o.integrator != "pamkit" && o.integrator != "dopri5") {
    throw std::invalid_argument("--integrator must be pamkit or dopri5, got " + o.integrator);
  }
  if (o.repeats < 1 || o.evaluations < 1 || o.evaluation_batches < 1) {
    throw std::invalid_argument("--repeats, --evaluations and --evaluation-batches must be >= 1");
  }
  return o;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void print_array(const char* name, const std::vector<double>& values) {
  std::printf("\"%s\": [", name);
  for (std::size_t k = 0; k < values.size(); ++k) std::printf(k == 0 ? "%.17g" : ", %.17g", values[k]);
  std::printf("]");
}

}  // namespace

int main(int argc, char** argv) try {
  const Options o = parse(argc, argv);

  pamkit::MuscleParams params;
  params.friction.sharpness_s_per_m = o.sharpness_s_per_m;
  params.gas.process = o.process == "polytropic" ? pamkit::GasProcess::polytropic : pamkit::GasProcess::heat_transfer;
  params.gas.heat_transfer_time_constant_s = o.tau_s;
  params.gas.polytropic_index = o.polytropic_index;
  pamkit::InitialState initial;
  initial.length_m = o.length_m;
  initial.gauge_pressure_Pa = o.gauge_pressure_Pa;
  const pamkit::MuscleModel model(params, initial);
  const pamkit::ElongationTrajectory trajectory =
      pamkit::thesis_protocol(o.max_elongation_m, o.speed_m_per_s, o.cycles, o.sample_period_s);
  pamkit::SimulatorConfig config;
  config.relative_tolerance = o.rtol;
  config.absolute_tolerance_K = o.atol_K;
  config.absolute_tolerance_J = o.atol_J;
  config.method = o.method == "bdf"           ? pamkit::IntegrationMethod::bdf
                  : o.method == "adams"       ? pamkit::IntegrationMethod::adams
                  : o.method == "dopri5"      ? pamkit::IntegrationMethod::dopri5
                  : o.method == "rosenbrock4" ? pamkit::IntegrationMethod::rosenbrock4
                                              : pamkit::IntegrationMethod::automatic;
  const pamkit::Simulator simulator(config);

  if (o.integrator == "dopri5") {
    pamkit_bench::Dopri5Run run;
    double best = 1e300;
    for (int r = 0; r < o.repeats; ++r) {
      const auto start = std::chrono::steady_clock::now();
      run = pamkit_bench::dopri5_run(model, trajectory, o.rtol, o.atol_K, config.corner_threshold);
      best = std::min(best, seconds_since(start));
    }
    std::printf(
        "{\"integrator\": \"dopri5\", \"simulate_s\": %.9g, \"samples\": %zu, \"steps\": %ld, "
        "\"rhs_evaluations\": %ld, \"rtol\": %.3g, \"repeats\": %d, ",
        best, run.force_N.size(), run.steps, run.rhs_evaluations, o.rtol, o.repeats);
    print_array("force_N", run.force_N);
    std::printf(", ");
    print_array("gauge_pressure_Pa", run.gauge_pressure_Pa);
    std::printf(", ");
    print_array("temperature_K", run.temperature_K);
    std::printf("}\n");
    return 0;
  }

  // The whole simulation, best of `repeats` (the first run also warms the caches).
  pamkit::SimulationResult result;
  double best_run = 1e300;
  for (int r = 0; r < o.repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    result = simulator.run(model, trajectory);
    best_run = std::min(best_run, seconds_since(start));
  }

  // One RHS evaluation: the states the run visits (its lengths, rates and temperatures),
  // cycled so the geometry's Newton solve sees the same spread of starting guesses.
  const std::size_t samples = result.time_s.size();
  std::vector<double> velocity(samples);
  for (std::size_t k = 0; k < samples; ++k) velocity[k] = trajectory.segment_velocity(k == 0 ? 0 : k - 1);
  double sink = 0.0;
  double best_evaluation = 1e300;
  for (int b = 0; b < o.evaluation_batches; ++b) {
    const auto start = std::chrono::steady_clock::now();
    for (long i = 0; i < o.evaluations; ++i) {
      const std::size_t k = static_cast<std::size_t>(i) % samples;
      pamkit::State state = model.initial();
      state[pamkit::State::temperature_K] = result.temperature_K[k];
      const pamkit::MuscleOutputs out = model.evaluate(result.length_m[k], velocity[k], state);
      sink += out.forces.total + out.rate[pamkit::State::temperature_K] + out.heat_loss_rate_W;
    }
    best_evaluation = std::min(best_evaluation, seconds_since(start) / static_cast<double>(o.evaluations));
  }

  // One evaluation as the simulator's right-hand side makes it: started from the previous one's
  // braid solve (a MuscleWorkspace), the shape's kinematics only, the run's states in order.
  double best_warm_evaluation = 1e300;
  for (int b = 0; b < o.evaluation_batches; ++b) {
    pamkit::MuscleWorkspace workspace;
    const auto start = std::chrono::steady_clock::now();
    for (long i = 0; i < o.evaluations; ++i) {
      const std::size_t k = static_cast<std::size_t>(i) % samples;
      pamkit::State state = model.initial();
      state[pamkit::State::temperature_K] = result.temperature_K[k];
      const pamkit::MuscleOutputs out =
          model.evaluate_with(workspace, result.length_m[k], velocity[k], state, pamkit::ShapeParts::kinematics);
      sink += out.forces.total + out.rate[pamkit::State::temperature_K] + out.heat_loss_rate_W;
    }
    best_warm_evaluation = std::min(best_warm_evaluation, seconds_since(start) / static_cast<double>(o.evaluations));
  }

  const pamkit::SolverStatistics& s = result.statistics;
  std::printf(
      "{\"simulate_s\": %.9g, \"evaluate_s\": %.9g, \"evaluate_warm_s\": %.9g, \"samples\": %zu, \"steps\": %ld, "
      "\"rhs_evaluations\": %ld, \"output_evaluations\": %ld, "
      "\"jacobian_evaluations\": %ld, \"linear_solver_setups\": %ld, \"nonlinear_iterations\": %ld, "
      "\"error_test_failures\": %ld, \"nonlinear_convergence_failures\": %ld, "
      "\"restarts\": %ld, \"final_force_N\": %.17g, \"final_temperature_K\": %.17g, \"process\": \"%s\", "
      "\"method\": \"%s\", \"rtol\": %.3g, \"repeats\": %d, \"sink\": %.6g}\n",
      best_run, best_evaluation, best_warm_evaluation, samples, s.steps, s.rhs_evaluations, s.output_evaluations,
      s.jacobian_evaluations, s.linear_solver_setups, s.nonlinear_iterations, s.error_test_failures,
      s.nonlinear_convergence_failures, s.restarts, result.force_N.back(), result.temperature_K.back(),
      o.process.c_str(), pamkit::to_string(s.method), o.rtol, o.repeats, sink);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "pamkit_bench_simulate: %s\n", e.what());
  return 1;
}
