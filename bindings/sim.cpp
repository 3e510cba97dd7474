// Bindings of include/pamkit/sim: the model, trajectories and the CVODES simulator. Results
// come back as numpy arrays that view the C++ vectors (no copy); runs release the GIL.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <sstream>

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
                               "iteration), dopri5 (explicit Dormand-Prince 5(4) with dense output, Boost.Odeint), or "
                               "auto (dopri5 where estimate_stiffness finds the run non-stiff, bdf otherwise).")
      .value("auto", IntegrationMethod::automatic)
      .value("bdf", IntegrationMethod::bdf)
      .value("adams", IntegrationMethod::adams)
      .value("dopri5", IntegrationMethod::dopri5);

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
      .def_property_readonly("stiff", &StiffnessEstimate::stiff, "ratio > 1: auto runs bdf")
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

  py::class_<SolverStatistics>(m, "SolverStatistics", "The integrator's counters over one run.")
      .def_readonly("method", &SolverStatistics::method, "the method that ran: bdf, adams or dopri5")
      .def_readonly("steps", &SolverStatistics::steps)
      .def_readonly("rhs_evaluations", &SolverStatistics::rhs_evaluations)
      .def_readonly("jacobian_evaluations", &SolverStatistics::jacobian_evaluations)
      .def_readonly("linear_solver_setups", &SolverStatistics::linear_solver_setups)
      .def_readonly("error_test_failures", &SolverStatistics::error_test_failures)
      .def_readonly("nonlinear_iterations", &SolverStatistics::nonlinear_iterations)
      .def_readonly("nonlinear_convergence_failures", &SolverStatistics::nonlinear_convergence_failures)
      .def_readonly("restarts", &SolverStatistics::restarts)
      .def_readonly("output_evaluations", &SolverStatistics::output_evaluations)
      .def_readonly("tabulated_shapes", &SolverStatistics::tabulated_shapes,
                    "output evaluations whose braid shape a ShapeTable gave (0: none, or it did not apply)")
      .def_readonly("sensitivity_rhs_evaluations", &SolverStatistics::sensitivity_rhs_evaluations,
                    "moved models' right-hand sides for the sensitivities (Simulator.run_sensitivities; 0 otherwise)")
      .def("__repr__", [](const SolverStatistics& s) {
        return std::string("SolverStatistics(method=") + to_string(s.method) + ", steps=" + std::to_string(s.steps) +
               ", rhs_evaluations=" + std::to_string(s.rhs_evaluations) +
               ", jacobian_evaluations=" + std::to_string(s.jacobian_evaluations) +
               ", error_test_failures=" + std::to_string(s.error_test_failures) +
               ", nonlinear_convergence_failures=" + std::to_string(s.nonlinear_convergence_failures) +
               ", restarts=" + std::to_string(s.restarts) + ")";
      });

  py::class_<SimulationResult> result(m, "SimulationResult",
                                      "Time series of one run, one entry per trajectory sample.");
#define PAMKIT_RESULT_COLUMN(name, doc) \
  result.def_property_readonly(         \
      #name, [](py::object self) { return view(self.cast<const SimulationResult&>().name, self); }, doc)
  PAMKIT_RESULT_COLUMN(time_s, "sample times [s]");
  PAMKIT_RESULT_COLUMN(elongation_m, "prescribed elongation [m]");
  PAMKIT_RESULT_COLUMN(length_m, "muscle length [m]");
  PAMKIT_RESULT_COLUMN(force_N, "axial force, tension > 0, friction included [N]");
  PAMKIT_RESULT_COLUMN(friction_force_N, "friction part of the force [N]");
  PAMKIT_RESULT_COLUMN(gauge_pressure_Pa, "gas pressure above ambient [Pa]");
  PAMKIT_RESULT_COLUMN(temperature_K, "gas temperature [K]");
  PAMKIT_RESULT_COLUMN(gas_volume_m3, "gas volume, dead volume included [m^3]");
  PAMKIT_RESULT_COLUMN(gas_mass_kg, "mass of air inside [kg]");
  PAMKIT_RESULT_COLUMN(braid_angle_rad, "braid angle of the cylinder [rad]");
  PAMKIT_RESULT_COLUMN(diameter_m, "braid diameter [m]");
  PAMKIT_RESULT_COLUMN(work_J, "work done on the muscle since the start [J]");
  PAMKIT_RESULT_COLUMN(heat_lost_J, "heat from gas to wall since the start [J]");
  PAMKIT_RESULT_COLUMN(friction_dissipated_J, "friction work since the start [J]");
#undef PAMKIT_RESULT_COLUMN
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

  py::class_<Simulator>(m, "Simulator", "Integrates a MuscleModel along a trajectory with CVODES. Re-entrant.")
      .def(py::init<SimulatorConfig>(), py::arg("config") = SimulatorConfig{})
      .def("run", &Simulator::run, py::arg("model"), py::arg("trajectory"), py::arg("shapes") = nullptr,
           py::call_guard<py::gil_scoped_release>(),
           "Simulates the model along the trajectory; releases the GIL while it runs. shapes: a ShapeTable whose "
           "braid shapes the samples read where it applies to this run (statistics.tabulated_shapes counts them), "
           "with the same result bit for bit; None or a table that does not apply: the shapes are solved.")
      .def("run_sensitivities", &Simulator::run_sensitivities, py::arg("model"), py::arg("moved"), py::arg("steps"),
           py::arg("trajectory"), py::arg("shapes") = nullptr,
           py::arg("moved_motions") = std::vector<ElongationTrajectory>{}, py::call_guard<py::gil_scoped_release>(),
           "run, with the forward sensitivities of every output column to parameters integrated by CVODES beside the "
           "state (BDF, staggered corrector, on the state's own steps: outside the error test, so the run is the plain "
           "run's to rounding). Parameter i is given as moved[i], the model with it "
           "moved by steps[i] (signed; its own initial state follows); each sensitivity's right-hand side and output "
           "derivative is the directional difference quotient (f_i(y + h_i s_i) - f(y)) / h_i. Parameters should be "
           "of order one (the sensitivities share the state's absolute tolerances); steps near 1e-6 give derivatives "
           "to ~1e-6 relative. moved_motions: where a parameter moves the muscle's motion (a fixture's slack), "
           "moved model i's elongation on the trajectory's times (its derivative's elongation_m is the motion's); "
           "empty: every moved model follows the trajectory. Returns a SensitivityResult; releases the GIL. "
           "ValueError for mismatched sizes, a zero step, a moved motion on other times or a moved model whose "
           "motion leaves its braid's range.")
      .def_property_readonly("config", &Simulator::config);
}

}  // namespace pamkit::python
