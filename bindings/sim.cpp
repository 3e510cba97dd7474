// Bindings of include/pamkit/sim: the model, trajectories and the CVODES simulator. Results
// come back as numpy arrays that view the C++ vectors (no copy); runs release the GIL.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bind_fields.hpp"
#include "pamkit/sim/simulator.hpp"

namespace py = pybind11;

namespace pamkit::python {
namespace {

/// A read-only numpy view of `vector`, kept alive by `owner`.
py::array_t<double> view(const std::vector<double>& vector, py::handle owner) {
  py::array_t<double> array(static_cast<py::ssize_t>(vector.size()), vector.data(), owner);
  array.attr("setflags")(py::arg("write") = false);
  return array;
}

std::vector<double> to_vector(const py::array_t<double, py::array::c_style | py::array::forcecast>& a,
                              const char* name) {
  if (a.ndim() != 1)
    throw py::value_error(std::string(name) + " must be a 1-D array, got " + std::to_string(a.ndim()) + " dimensions");
  return {a.data(), a.data() + a.size()};
}

}  // namespace

void bind_sim(py::module_& m) {
  // Bound before MuscleParams, whose signatures name it.
  py::class_<ModelExtensions> extensions(
      m, "ModelExtensions", "Physics beyond the thesis's model, all off (zero) by default; effects switch them on.");
  bind_fields(extensions);
  py::class_<MuscleParams>(m, "MuscleParams", "Everything that defines a muscle: build, bladder law, friction, gas.")
      .def(py::init<>())
      .def(py::init([](const MuscleBuild& build, const BladderLaw& bladder, const FrictionParams& friction,
                       const GasParams& gas) {
             return MuscleParams{build, bladder, friction, gas, ModelExtensions{}};
           }),
           py::arg("build") = MuscleBuild{}, py::arg("bladder") = BladderLaw::thesis(),
           py::arg("friction") = FrictionParams{}, py::arg("gas") = GasParams{})
      .def(py::init([](const MuscleBuild& build, const BladderLaw& bladder, const FrictionParams& friction,
                       const GasParams& gas, const ModelExtensions& extensions) {
             return MuscleParams{build, bladder, friction, gas, extensions};
           }),
           py::arg("build"), py::arg("bladder"), py::arg("friction"), py::arg("gas"), py::arg("extensions"))
      .def_readwrite("build", &MuscleParams::build)
      .def_readwrite("bladder", &MuscleParams::bladder)
      .def_readwrite("friction", &MuscleParams::friction)
      .def_readwrite("gas", &MuscleParams::gas)
      .def_readwrite("extensions", &MuscleParams::extensions)
      .def("validate", &MuscleParams::validate);

  py::class_<InitialState> initial(m, "InitialState", "The test at zero elongation: inflated, sealed, at rest.");
  bind_fields(initial);
  m.def("inflated_and_sealed", &inflated_and_sealed, py::arg("params"), py::arg("gauge_pressure_Pa"),
        "The start of a sealed test: inflated freely to gauge_pressure_Pa [Pa], sealed at the free length it gives.");

  py::class_<State> state(m, "State",
                          "ODE state: gas temperature and mass, bladder viscous stresses, energy integrals (SI).");
  state.def(py::init<>())
      .def(py::init([](const std::array<double, State::size>& values) { return State{values}; }), py::arg("values"))
      .def_readwrite("values", &State::values, "the state as a list, in the order of the index constants")
      .def("__getitem__", [](const State& s, int i) {
        if (i < 0 || i >= State::size) throw py::index_error("State index " + std::to_string(i) + " out of range");
        return s[i];
      });
  for (auto [name, index] : {std::pair{"temperature_K", State::temperature_K},
                             {"gas_mass_kg", State::gas_mass_kg},
                             {"viscous_stress_l_Pa", State::viscous_stress_l_Pa},
                             {"viscous_stress_h_Pa", State::viscous_stress_h_Pa},
                             {"work_J", State::work_J},
                             {"heat_lost_J", State::heat_lost_J},
                             {"friction_dissipated_J", State::friction_dissipated_J}}) {
    state.attr(name) = static_cast<int>(index);
  }

  py::class_<MuscleOutputs>(m, "MuscleOutputs", "What the model says at one instant (SI units).")
      .def_readonly("shape", &MuscleOutputs::shape)
      .def_readonly("forces", &MuscleOutputs::forces)
      .def_readonly("fiber_length_m", &MuscleOutputs::fiber_length_m)
      .def_readonly("fiber_length_rate_m_per_s", &MuscleOutputs::fiber_length_rate_m_per_s)
      .def_readonly("fiber_tension_N", &MuscleOutputs::fiber_tension_N)
      .def_readonly("gas_volume_m3", &MuscleOutputs::gas_volume_m3)
      .def_readonly("absolute_pressure_Pa", &MuscleOutputs::absolute_pressure_Pa)
      .def_readonly("gauge_pressure_Pa", &MuscleOutputs::gauge_pressure_Pa)
      .def_readonly("heat_loss_rate_W", &MuscleOutputs::heat_loss_rate_W)
      .def_readonly("rate", &MuscleOutputs::rate, "d(state)/dt");

  py::class_<MuscleModel>(m, "MuscleModel", "A muscle in a test: parameters and the sealed gas mass. Immutable.")
      .def(py::init<const MuscleParams&, const InitialState&>(), py::arg("params"), py::arg("initial"))
      .def("evaluate", &MuscleModel::evaluate, py::arg("length_m"), py::arg("velocity_m_per_s"), py::arg("state"),
           "Outputs and d(state)/dt at a length [m], elongation rate [m/s] and state.")
      .def("initial", &MuscleModel::initial, "the state at zero elongation")
      .def_property_readonly("dead_volume", &MuscleModel::dead_volume, "dead gas volume [m^3]")
      .def_property_readonly("gas_mass", &MuscleModel::gas_mass, "sealed air mass [kg]")
      .def_property_readonly("initial_gas_volume", &MuscleModel::initial_gas_volume,
                             "gas volume at zero elongation [m^3]")
      .def_property_readonly("initial_temperature", &MuscleModel::initial_temperature,
                             "gas temperature at the start [K]")
      .def_property_readonly("params", &MuscleModel::params)
      .def_property_readonly("initial_state", &MuscleModel::initial_state)
      .def_property_readonly("geometry", &MuscleModel::geometry);

  py::class_<ElongationTrajectory>(m, "ElongationTrajectory",
                                   "Elongation [m] against time [s], linear between samples.")
      .def(py::init([](const py::array_t<double, py::array::c_style | py::array::forcecast>& time_s,
                       const py::array_t<double, py::array::c_style | py::array::forcecast>& elongation_m) {
             return ElongationTrajectory(to_vector(time_s, "time_s"), to_vector(elongation_m, "elongation_m"));
           }),
           py::arg("time_s"), py::arg("elongation_m"))
      .def_property_readonly(
          "time_s", [](py::object self) { return view(self.cast<const ElongationTrajectory&>().time(), self); })
      .def_property_readonly(
          "elongation_m",
          [](py::object self) { return view(self.cast<const ElongationTrajectory&>().elongation(), self); })
      .def("__len__", &ElongationTrajectory::size);
  m.def("thesis_protocol", &thesis_protocol, py::arg("max_elongation_m"), py::arg("speed_m_per_s") = 2.5e-3,
        py::arg("cycles") = 10, py::arg("sample_period_s") = 0.1, py::arg("hold_s") = 0.0,
        "The bench protocol of section 3.2.1: triangular stretch cycles at constant speed.");

  py::enum_<IntegrationMethod>(m, "IntegrationMethod",
                               "How a run is integrated: bdf (CVODES, dense Newton), adams (CVODES, fixed-point "
                               "iteration), dopri5 (explicit Dormand-Prince 5(4) with dense output, Boost.Odeint), "
                               "rosenbrock4 (Boost.Odeint's Rosenbrock 4(3), linearly implicit, on the states that "
                               "move and the energies), or auto (dopri5 where estimate_stiffness finds the run "
                               "non-stiff, else rosenbrock4, or bdf at a relative tolerance below 1e-9).")
      .value("auto", IntegrationMethod::automatic)
      .value("bdf", IntegrationMethod::bdf)
      .value("adams", IntegrationMethod::adams)
      .value("dopri5", IntegrationMethod::dopri5)
      .value("rosenbrock4", IntegrationMethod::rosenbrock4);

  py::class_<SimulatorConfig> config(m, "SimulatorConfig", "Integrator settings.");
  bind_fields(config);

  py::class_<StiffnessEstimate>(m, "StiffnessEstimate",
                                "The stiffness test of IntegrationMethod.auto: the model's fastest rate times the step "
                                "the tolerance allows on the trajectory's longest piece; above 1, stiff.")
      .def_readonly("fastest_rate_per_s", &StiffnessEstimate::fastest_rate_per_s,
                    "the model's fastest relaxation rate [1/s]")
      .def_readonly("longest_piece_s", &StiffnessEstimate::longest_piece_s,
                    "longest stretch between the trajectory's corners [s]")
      .def_readonly("expected_step_s", &StiffnessEstimate::expected_step_s,
                    "longest_piece_s * rtol^(1/6), at most max_step_s [s]")
      .def_property_readonly("ratio", &StiffnessEstimate::ratio, "fastest_rate_per_s * expected_step_s [1]")
      .def_property_readonly("stiff", &StiffnessEstimate::stiff,
                             "ratio > 1: auto runs rosenbrock4 (bdf below a relative tolerance of 1e-9)")
      .def("__repr__", [](const StiffnessEstimate& e) {
        std::ostringstream out;
        out << "StiffnessEstimate(fastest_rate_per_s=" << e.fastest_rate_per_s
            << ", longest_piece_s=" << e.longest_piece_s << ", expected_step_s=" << e.expected_step_s
            << ", ratio=" << e.ratio() << ", stiff=" << (e.stiff() ? "True" : "False") << ")";
        return out.str();
      });
  m.def("estimate_stiffness", &estimate_stiffness, py::arg("model"), py::arg("trajectory"),
        py::arg("config") = SimulatorConfig{},
        "The stiffness test SimulatorConfig(method=IntegrationMethod.auto) makes before a run.");

  py::class_<SolverStatistics> statistics(m, "SolverStatistics", "The integrator's counters over one run.");
  statistics.def_readonly("method", &SolverStatistics::method, "the method that ran: never auto");
  SolverStatistics::for_each_counter([&](const char* name, long SolverStatistics::*counter, const char* meaning) {
    statistics.def_readonly(name, counter, meaning);
  });
  statistics.def("__repr__", [](const SolverStatistics& s) {
    std::string out = std::string("SolverStatistics(method=") + to_string(s.method);
    SolverStatistics::for_each_counter([&](const char* name, long SolverStatistics::*counter, const char*) {
      out += std::string(", ") + name + "=" + std::to_string(s.*counter);
    });
    return out + ")";
  });

  py::class_<SimulationResult> result(m, "SimulationResult",
                                      "Time series of one run, one entry per trajectory sample.");
  SimulationResult::for_each_column([&](const char* name, std::vector<double> SimulationResult::*column,
                                        const char* unit, const char* meaning, bool) {
    result.def_property_readonly(
        name, [column](py::object self) { return view(self.cast<const SimulationResult&>().*column, self); },
        (std::string(meaning) + " [" + unit + "]").c_str());
  });
  result.def_readonly("statistics", &SimulationResult::statistics);

  py::class_<ShapeTable>(
      m, "ShapeTable",
      "The braid's shape (kinematics and cylinder braid angle) at every sample length initial_length_m + "
      "elongation_m[k] of a trajectory, solved once for one build and shared, immutable, by the runs along it that "
      "differ only in pressure, friction, bladder law, gas or effects that leave the build, the motion and the "
      "fibres' stiffness alone (Simulator.run, simulate_measurement: shapes=). A run that reads it gives the same "
      "numbers bit for bit; a run it does not apply to ignores it.")
      .def(py::init([](const MuscleBuild& build, double initial_length_m, const ElongationTrajectory& trajectory) {
             py::gil_scoped_release release;
             return ShapeTable(build, initial_length_m, trajectory);
           }),
           py::arg("build"), py::arg("initial_length_m"), py::arg("trajectory"),
           "Solves the shapes of `build` at initial_length_m [m] plus each elongation [m] of the muscle's trajectory "
           "(after any motion effect). Releases the GIL. ValueError naming a sample outside the braid's range.")
      .def(py::init([](const MuscleParams& params, double initial_length_m, const ElongationTrajectory& trajectory) {
             py::gil_scoped_release release;
             return ShapeTable(params.build, initial_length_m, trajectory);
           }),
           py::arg("params"), py::arg("initial_length_m"), py::arg("trajectory"),
           "The table of params.build (the rest of params does not shape the braid).")
      .def("applies_to", &ShapeTable::applies_to, py::arg("model"), py::arg("trajectory"),
           "Whether a run of `model` along `trajectory` reads its shapes here: the same build field for field, the "
           "same sample lengths bit for bit, inextensible fibres (fiber_compliance_per_N = 0).")
      .def(
          "shape",
          [](const ShapeTable& table, std::size_t k) {
            if (k >= table.size()) {
              throw py::index_error("ShapeTable.shape: sample " + std::to_string(k) + " of " +
                                    std::to_string(table.size()));
            }
            return table.shape(k);
          },
          py::arg("k"), "the shape at sample k (its end, cone and mean braid angles are NaN: not tabulated)")
      .def_property_readonly(
          "length_m", [](py::object self) { return view(self.cast<const ShapeTable&>().length_m(), self); },
          "muscle length at each sample [m]")
      .def_property_readonly("build", &ShapeTable::build)
      .def_property_readonly("initial_length_m", &ShapeTable::initial_length_m, "muscle length at zero elongation [m]")
      .def("__len__", &ShapeTable::size);

  py::class_<SensitivityResult>(m, "SensitivityResult",
                                "A run and its forward sensitivities (Simulator.run_sensitivities).")
      .def_readonly("run", &SensitivityResult::run, "the run at the nominal parameters")
      .def_property_readonly(
          "derivatives",
          [](py::object self) {
            // Views into the result, not copies: a long record's derivatives are megabytes.
            py::list out;
            for (const SimulationResult& d : self.cast<const SensitivityResult&>().derivatives) {
              out.append(py::cast(&d, py::return_value_policy::reference_internal, self));
            }
            return out;
          },
          "per parameter, a SimulationResult whose output columns are the derivatives of run's (per unit of the "
          "parameter); elongation_m is the muscle's motion's (zero unless moved_motions moves it), statistics empty. "
          "Views into this result, which they keep alive.");

  py::class_<ParameterSets>(m, "ParameterSets",
                            "One muscle's parameters and sealed start, varied run by run: each run sets its own "
                            "values of the named fields on a shared base (Simulator.run_batch).")
      .def(py::init([](const MuscleParams& base, const InitialState& start, const std::vector<std::string>& names,
                       const py::array_t<double, py::array::c_style | py::array::forcecast>& values,
                       bool inflated_start) {
             if (values.ndim() != 2 || static_cast<std::size_t>(values.shape(1)) != names.size()) {
               throw py::value_error("ParameterSets: values must be a 2-D array of one column per name (" +
                                     std::to_string(names.size()) + "), one row per run");
             }
             return ParameterSets(base, start, inflated_start, names,
                                  std::vector<double>(values.data(), values.data() + values.size()));
           }),
           py::arg("base"), py::arg("start"), py::arg("names"), py::arg("values"), py::arg("inflated_start") = false,
           "base: MuscleParams every run starts from; start: the InitialState every run shares but for the fields "
           "it sets; names: the fields each run sets, 'build.<MuscleBuild field>', 'build.braid_angle_deg' (the "
           "revolutions that give the deflated build this angle [deg], as fiber_revolutions_for_braid_angle takes "
           "it), 'bladder.shear_modulus_Pa' (a neo-Hookean bladder), 'friction.<field>', 'gas.<field>', "
           "'extensions.<field>', 'initial.length_m', 'initial.gauge_pressure_Pa'; values: (runs, len(names)), each "
           "in its field's unit; inflated_start: a run starts at the free length its pressure inflates the muscle to "
           "(inflated_and_sealed) unless it sets initial.length_m. ValueError for an unknown or repeated name.")
      .def_property_readonly("runs", &ParameterSets::runs, "how many runs")
      .def_property_readonly("names", &ParameterSets::names, "the fields each run sets, in the values' column order")
      .def("at", &ParameterSets::at, py::arg("run"),
           "Run `run`'s (MuscleParams, InitialState), as run_batch makes them. ValueError for a value its field or "
           "the muscle refuses, IndexError past the last run.");

  py::enum_<RunFailure>(m, "RunFailure", "Why a run of Simulator.run_batch failed.")
      .value("none", RunFailure::none, "it ran")
      .value("parameters", RunFailure::parameters,
             "its parameters were refused before a model was built (a field out of its range, a braid angle the "
             "build cannot reach, a pressure it cannot inflate to freely)")
      .value("input", RunFailure::input, "the model could not follow the trajectory (outside the braid's range)")
      .value("solver", RunFailure::solver, "the integrator failed");

  py::class_<BatchResult>(m, "BatchResult",
                          "The runs of Simulator.run_batch, in the order given; arrays have one row per run.")
      .def_readonly("runs", &BatchResult::runs, "how many runs")
      .def_readonly("channels", &BatchResult::channels, "the channels kept, in the order asked")
      .def_property_readonly(
          "rows",
          [](const BatchResult& r) {
            return py::array_t<std::size_t>(static_cast<py::ssize_t>(r.rows.size()), r.rows.data());
          },
          "the sample indices each channel is kept at")
      .def_property_readonly(
          "values",
          [](py::object self) {
            const auto& r = self.cast<const BatchResult&>();
            py::dict out;
            const auto shape =
                std::vector<py::ssize_t>{static_cast<py::ssize_t>(r.runs), static_cast<py::ssize_t>(r.rows.size())};
            for (std::size_t c = 0; c < r.channels.size(); ++c) {
              py::array_t<double> array(shape, r.values[c].data(), self);
              array.attr("setflags")(py::arg("write") = false);
              out[py::str(r.channels[c])] = array;
            }
            return out;
          },
          "channel name -> (runs, len(rows)) array of its values at the rows (NaN for a failed run); views into "
          "this result")
      .def_property_readonly(
          "maximum",
          [](py::object self) {
            const auto& r = self.cast<const BatchResult&>();
            py::dict out;
            for (std::size_t c = 0; c < r.channels.size(); ++c) out[py::str(r.channels[c])] = view(r.maximum[c], self);
            return out;
          },
          "channel name -> (runs,) array of each run's largest value over every sample (NaN for a failed run)")
      .def_property_readonly(
          "minimum",
          [](py::object self) {
            const auto& r = self.cast<const BatchResult&>();
            py::dict out;
            for (std::size_t c = 0; c < r.channels.size(); ++c) out[py::str(r.channels[c])] = view(r.minimum[c], self);
            return out;
          },
          "channel name -> (runs,) array of each run's smallest value over every sample")
      .def_property_readonly(
          "statistics",
          [](const BatchResult& r) {
            py::dict out;
            py::array_t<int> methods(static_cast<py::ssize_t>(r.runs));
            auto method = methods.mutable_unchecked<1>();
            for (std::size_t i = 0; i < r.runs; ++i)
              method(static_cast<py::ssize_t>(i)) = static_cast<int>(r.statistics[i].method);
            out["method"] = methods;
            SolverStatistics::for_each_counter([&](const char* name, long SolverStatistics::*counter, const char*) {
              py::array_t<long> values(static_cast<py::ssize_t>(r.runs));
              auto value = values.mutable_unchecked<1>();
              for (std::size_t i = 0; i < r.runs; ++i) value(static_cast<py::ssize_t>(i)) = r.statistics[i].*counter;
              out[name] = values;
            });
            return out;
          },
          "counter name (SolverStatistics's) -> (runs,) array of each run's count, and 'method': each run's "
          "IntegrationMethod as its integer value (zero counters for a failed run)")
      .def_readonly("errors", &BatchResult::errors, "per run, why it failed; '' where it ran")
      .def_property_readonly(
          "failed",
          [](const BatchResult& r) {
            py::array_t<bool> out(static_cast<py::ssize_t>(r.runs));
            auto flag = out.mutable_unchecked<1>();
            for (std::size_t i = 0; i < r.runs; ++i) flag(static_cast<py::ssize_t>(i)) = !r.errors[i].empty();
            return out;
          },
          "(runs,) bool: the run failed (its message in errors)")
      .def_property_readonly(
          "failures",
          [](const BatchResult& r) {
            py::array_t<std::uint8_t> out(static_cast<py::ssize_t>(r.runs));
            auto kind = out.mutable_unchecked<1>();
            for (std::size_t i = 0; i < r.runs; ++i)
              kind(static_cast<py::ssize_t>(i)) = static_cast<std::uint8_t>(r.failures[i]);
            return out;
          },
          "(runs,) RunFailure values: why each run failed (0 none: it ran)")
      .def_property_readonly(
          "rejected",
          [](const BatchResult& r) {
            py::array_t<bool> out(static_cast<py::ssize_t>(r.runs));
            auto flag = out.mutable_unchecked<1>();
            for (std::size_t i = 0; i < r.runs; ++i) {
              flag(static_cast<py::ssize_t>(i)) = r.failures[i] == RunFailure::parameters;
            }
            return out;
          },
          "(runs,) bool: failures == RunFailure.parameters, its parameters refused before a model was built");

  py::class_<Simulator>(m, "Simulator", "Integrates a MuscleModel along a trajectory with CVODES. Re-entrant.")
      .def(py::init<SimulatorConfig>(), py::arg("config") = SimulatorConfig{})
      .def("run", &Simulator::run, py::arg("model"), py::arg("trajectory"), py::arg("shapes") = nullptr,
           py::call_guard<py::gil_scoped_release>(),
           "Simulates the model along the trajectory; releases the GIL while it runs. shapes: a ShapeTable whose "
           "braid shapes the samples read where it applies to this run (statistics.tabulated_shapes counts them), "
           "with the same result bit for bit; None or a table that does not apply: the shapes are solved.")
      .def("run_sensitivities", &Simulator::run_sensitivities, py::arg("model"), py::arg("moved"), py::arg("steps"),
           py::arg("trajectory"), py::arg("shapes") = nullptr,
           py::arg("moved_motions") = std::vector<ElongationTrajectory>{}, py::arg("rows") = std::vector<std::size_t>{},
           py::call_guard<py::gil_scoped_release>(),
           "run, with the forward sensitivities of every output column to parameters integrated by CVODES beside the "
           "state (BDF, staggered corrector, on the state's own steps: outside the error test, so the run is the plain "
           "run's to rounding). Parameter i is given as moved[i], the model with it "
           "moved by steps[i] (signed; its own initial state follows); each sensitivity's right-hand side and output "
           "derivative is the directional difference quotient (f_i(y + h_i s_i) - f(y)) / h_i. Parameters should be "
           "of order one (the sensitivities share the state's absolute tolerances); steps near 1e-6 give derivatives "
           "to ~1e-6 relative. moved_motions: where a parameter moves the muscle's motion (a fixture's slack), "
           "moved model i's elongation on the trajectory's times (its derivative's elongation_m is the motion's); "
           "empty: every moved model follows the trajectory. rows: the samples (increasing indices) whose "
           "derivatives are read, NaN at the others, which cost nothing (empty: every sample). Returns a "
           "SensitivityResult; releases the GIL. ValueError for mismatched sizes, a zero step, a moved motion on other "
           "times, a moved model whose motion leaves its braid's range, or rows that do not increase or pass the end.")
      .def(
          "run_batch",
          [](const Simulator& simulator, const std::vector<MuscleModel>& models, const ElongationTrajectory& trajectory,
             const std::vector<std::string>& channels, const std::optional<std::vector<std::size_t>>& rows,
             std::size_t threads, const ShapeTable* shapes, const std::vector<ElongationTrajectory>& motions) {
            const BatchRequest request{channels, rows.value_or(std::vector<std::size_t>{}), threads};
            py::gil_scoped_release release;
            return simulator.run_batch(models, trajectory, request, shapes, motions);
          },
          py::arg("models"), py::arg("trajectory"), py::arg("channels") = BatchRequest{}.channels,
          py::arg("rows") = py::none(), py::arg("threads") = 0, py::arg("shapes") = nullptr,
          py::arg("motions") = std::vector<ElongationTrajectory>{},
          "Runs every model along the trajectory on `threads` C++ threads (0: one per hardware thread), the GIL "
          "released, and keeps of each run the channels (SimulationResult's output columns, by name) at the sample "
          "indices `rows` (increasing; None: none) and their largest and smallest values over every sample: a "
          "BatchResult, each run's numbers Simulator.run's bit for bit whatever the threads. A run that fails keeps "
          "its message and NaN; the others run. shapes: a ShapeTable for every run it applies to; motions: run i "
          "follows motions[i] (on the trajectory's times). ValueError for an unknown channel, rows that do not "
          "increase or pass the end, or motions that are neither empty nor one per model.")
      .def(
          "run_batch",
          [](const Simulator& simulator, const ParameterSets& sets, const ElongationTrajectory& trajectory,
             const std::vector<std::string>& channels, const std::optional<std::vector<std::size_t>>& rows,
             std::size_t threads) {
            const BatchRequest request{channels, rows.value_or(std::vector<std::size_t>{}), threads};
            py::gil_scoped_release release;
            return simulator.run_batch(sets, trajectory, request);
          },
          py::arg("sets"), py::arg("trajectory"), py::arg("channels") = BatchRequest{}.channels,
          py::arg("rows") = py::none(), py::arg("threads") = 0,
          "run_batch over the runs of a ParameterSets, each run's muscle made on the C++ thread that runs it "
          "(ParameterSets.at): a design sweep with no Python per run. A run whose parameters are refused is marked "
          "in BatchResult.failures as RunFailure.parameters.")
      .def_property_readonly("config", &Simulator::config);
}

}  // namespace pamkit::python
