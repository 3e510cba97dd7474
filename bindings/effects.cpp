// Bindings of include/pamkit/effects: the Effect interface (subclassable from Python), the
// built-in catalog, and the simulated measurement.

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>

#include "bind_fields.hpp"
#include "pamkit/effects/catalog.hpp"
#include "pamkit/effects/isotonic_motion.hpp"
#include "pamkit/effects/pipeline.hpp"

namespace py = pybind11;

namespace pamkit::python {
namespace {

/// Lets Python classes derive from pamkit.Effect; each override is looked up by name.
class PyEffect : public Effect {
 public:
  std::string name() const override { PYBIND11_OVERRIDE_PURE(std::string, Effect, name, ); }
  std::string description() const override { PYBIND11_OVERRIDE_PURE(std::string, Effect, description, ); }
  std::vector<EffectParameter> parameters() const override {
    PYBIND11_OVERRIDE_PURE(std::vector<EffectParameter>, Effect, parameters, );
  }
  std::map<std::string, std::string> options() const override {
    PYBIND11_OVERRIDE(PYBIND11_TYPE(std::map<std::string, std::string>), Effect, options, );
  }
  void set(const std::string& key, const std::string& value) override {
    PYBIND11_OVERRIDE_PURE(void, Effect, set, key, value);
  }
  std::string signature() const override { PYBIND11_OVERRIDE(std::string, Effect, signature, ); }
  std::vector<std::string> channels_changed() const override {
    PYBIND11_OVERRIDE(std::vector<std::string>, Effect, channels_changed, );
  }
  /// A Python effect may say its stage ("physics", "motion", "measurement"); if it does not,
  /// the stage is the earliest one it overrides.
  EffectStage stage() const override {
    py::gil_scoped_acquire gil;
    const auto* self = static_cast<const Effect*>(this);
    if (py::function override = py::get_override(self, "stage")) return override().cast<EffectStage>();
    if (py::get_override(self, "apply_to_params")) return EffectStage::physics;
    if (py::get_override(self, "apply_to_elongation")) return EffectStage::motion;
    if (py::get_override(self, "apply_to_measurement")) return EffectStage::measurement;
    return EffectStage::physics;
  }
  /// A Python effect that overrides apply_to_measurement reads each sample alone only if it
  /// says so (reads_samples_alone).
  bool reads_samples_alone() const override {
    py::gil_scoped_acquire gil;
    const auto* self = static_cast<const Effect*>(this);
    if (py::function override = py::get_override(self, "reads_samples_alone")) return override().cast<bool>();
    return !py::get_override(self, "apply_to_measurement");
  }
  bool acts_in(GasMode mode, std::string* why_not) const override {
    py::gil_scoped_acquire gil;
    py::function override = py::get_override(static_cast<const Effect*>(this), "why_not");
    if (!override) return true;
    const py::object reason = override(mode == GasMode::sealed ? "sealed" : "supplied");
    if (reason.is_none()) return true;
    if (why_not) *why_not = reason.cast<std::string>();
    return false;
  }
  void apply_to_params(MuscleParams& params) const override {
    py::gil_scoped_acquire gil;
    py::function override = py::get_override(static_cast<const Effect*>(this), "apply_to_params");
    if (override) params = override(params).cast<MuscleParams>();
  }
  std::vector<double> apply_to_elongation(const std::vector<double>& time_s,
                                          const std::vector<double>& crosshead_m) const override {
    PYBIND11_OVERRIDE(std::vector<double>, Effect, apply_to_elongation, time_s, crosshead_m);
  }
  void apply_to_measurement(Measurement& measurement) const override {
    py::gil_scoped_acquire gil;
    py::function override = py::get_override(static_cast<const Effect*>(this), "apply_to_measurement");
    if (override) measurement = override(measurement).cast<Measurement>();
  }
};

// Numbers in from any sequence numpy can read, copied once through its buffer.
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

py::array_t<double> copy(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}
std::vector<double> vector(const Array& a) { return {a.data(), a.data() + a.size()}; }

}  // namespace

void bind_effects(py::module_& m) {
  py::enum_<GasMode>(m, "GasMode", "How the muscle's gas is held during a test.")
      .value("sealed", GasMode::sealed)
      .value("supplied", GasMode::supplied);

  py::class_<Measurement>(m, "Measurement",
                          "Channels of a bench test on one time base (numpy arrays, copied in and out).")
      .def(py::init<>())
#define PAMKIT_CHANNEL(name, doc)                               \
  def_property(                                                 \
      #name, [](const Measurement& s) { return copy(s.name); }, \
      [](Measurement& s, const Array& a) { s.name = vector(a); }, doc)
      .PAMKIT_CHANNEL(time_s, "sample times [s]")
      .PAMKIT_CHANNEL(elongation_m, "the crosshead's elongation [m]")
      .PAMKIT_CHANNEL(force_N, "load cell [N]")
      .PAMKIT_CHANNEL(gauge_pressure_Pa, "pressure transducer: above the atmosphere [Pa]")
      .PAMKIT_CHANNEL(temperature_K, "gas temperature sensor [K]")
      .def_readonly("statistics", &Measurement::statistics,
                    "CVODES counters of the run behind a sealed test; all zero for a supplied test (no ODE)");
#undef PAMKIT_CHANNEL
  m.def("measured_channels", &measured_channels, "names of the channels effects may act on");

  py::enum_<EffectStage>(m, "EffectStage", "Where an effect acts in a simulated measurement.")
      .value("physics", EffectStage::physics, "the model's parameters and states")
      .value("motion", EffectStage::motion, "the motion between crosshead and muscle")
      .value("measurement", EffectStage::measurement, "what the instruments read");
  py::enum_<FitScale>(m, "FitScale", "The scale on which a diagnosis moves a parameter.")
      .value("linear", FitScale::linear)
      .value("log", FitScale::log, "time constants and stiffnesses that span decades")
      .value("reciprocal", FitScale::reciprocal, "'infinity means off' constants, fitted as a rate");
  py::enum_<Resolution>(m, "Resolution", "What a record must resolve for a fitted value to mean something.")
      .value("any", Resolution::any)
      .value("sample_interval", Resolution::sample_interval, "|value| [s] at least the sample interval")
      .value("travel_per_sample", Resolution::travel_per_sample, "value [m] at least the travel between samples");

  py::class_<EffectParameter>(m, "EffectParameter", R"doc(One parameter of an effect.

A Python effect declares at least name, value, unit, the allowed range (min, max) and the
realistic range synthetic benches draw from. It may also declare the physically plausible range
with its source (a fitted value outside it is reported, never named as a cause) and the
diagnosis's search (fit_scale, fit_min, fit_max, fit_start); left out, plausible is the allowed
range and the search is linear over the realistic range widened by its width on each side.)doc")
      .def(py::init([](std::string name, double value, std::string unit, double min, double max, double realistic_min,
                       double realistic_max, std::string description, bool either_sign,
                       std::optional<double> plausible_min, std::optional<double> plausible_max,
                       std::string plausible_source, std::optional<FitScale> fit_scale, std::optional<double> fit_min,
                       std::optional<double> fit_max, std::optional<double> fit_start, Resolution resolution) {
             EffectParameter p = EffectParameter::declared(std::move(name), value, std::move(unit), min, max,
                                                           realistic_min, realistic_max, std::move(description));
             p.either_sign = either_sign;
             if (plausible_min) p.plausible_min = *plausible_min;
             if (plausible_max) p.plausible_max = *plausible_max;
             if (!plausible_source.empty()) p.plausible_source = std::move(plausible_source);
             if (fit_scale) p.fit_scale = *fit_scale;
             if (fit_min) p.fit_min = *fit_min;
             if (fit_max) p.fit_max = *fit_max;
             if (fit_start) p.fit_start = *fit_start;
             p.resolution = resolution;
             return p;
           }),
           py::arg("name"), py::arg("value"), py::arg("unit"), py::arg("min"), py::arg("max"), py::arg("realistic_min"),
           py::arg("realistic_max"), py::arg("description") = "", py::kw_only(), py::arg("either_sign") = false,
           py::arg("plausible_min") = py::none(), py::arg("plausible_max") = py::none(),
           py::arg("plausible_source") = "", py::arg("fit_scale") = py::none(), py::arg("fit_min") = py::none(),
           py::arg("fit_max") = py::none(), py::arg("fit_start") = py::none(), py::arg("resolution") = Resolution::any)
      .def_readonly("name", &EffectParameter::name)
      .def_readonly("value", &EffectParameter::value)
      .def_readonly("unit", &EffectParameter::unit)
      .def_readonly("min", &EffectParameter::min, "smallest allowed value")
      .def_readonly("max", &EffectParameter::max, "largest allowed value")
      .def_readonly("realistic_min", &EffectParameter::realistic_min, "smallest value synthetic benches draw")
      .def_readonly("realistic_max", &EffectParameter::realistic_max, "largest value synthetic benches draw")
      .def_readonly("description", &EffectParameter::description)
      .def_readonly("either_sign", &EffectParameter::either_sign, "the realistic range bounds |value|")
      .def_readonly("plausible_min", &EffectParameter::plausible_min, "smallest physically plausible value")
      .def_readonly("plausible_max", &EffectParameter::plausible_max, "largest physically plausible value")
      .def_readonly("plausible_source", &EffectParameter::plausible_source, "why that range")
      .def_readonly("fit_scale", &EffectParameter::fit_scale, "the diagnosis's search scale")
      .def_readonly("fit_min", &EffectParameter::fit_min, "the search's lower end (a fit ending here is at a bound)")
      .def_readonly("fit_max", &EffectParameter::fit_max, "the search's upper end")
      .def_readonly("fit_start", &EffectParameter::fit_start, "where the search starts")
      .def_readonly("resolution", &EffectParameter::resolution, "what one sample must resolve")
      .def_readonly("neutral", &EffectParameter::neutral,
                    "the value at which the parameter adds nothing (a zero offset, a unit gain); NaN where none does")
      .def("__repr__", [](const EffectParameter& p) { return p.name + "=" + std::to_string(p.value) + " " + p.unit; });

  py::class_<Effect, PyEffect, EffectPtr>(m, "Effect", R"doc(A model extension with physical parameters.

Subclass it in Python to add an effect: define name(), description(), parameters() (a list of
EffectParameter), set(key, value), and any of apply_to_params(params) -> params,
apply_to_elongation(time_s, crosshead_m) -> elongation_m, apply_to_measurement(measurement) -> measurement,
why_not(mode) -> None or a reason it cannot act in "sealed"/"supplied" tests.)doc")
      .def(py::init<>())
      .def("name", &Effect::name)
      .def("description", &Effect::description)
      .def("parameters", &Effect::parameters)
      .def("options", &Effect::options)
      .def("set", &Effect::set_value, py::arg("key"), py::arg("value"), "sets a numeric parameter")
      .def("set", &Effect::set, py::arg("key"), py::arg("value"), "sets a parameter or option from text")
      .def("stage", &Effect::stage, "where the effect acts: physics, motion or measurement")
      .def("channels_changed", &Effect::channels_changed, "the measured channels it changes ([]: all)")
      .def("signature", &Effect::signature, "a short phrase for a verdict (may name {channel})")
      .def(
          "acts_in",
          [](const Effect& e, GasMode mode) {
            std::string why;
            const bool ok = e.acts_in(mode, &why);
            return py::make_tuple(ok, ok ? py::none() : py::cast(why));
          },
          py::arg("mode"), "(True, None) or (False, reason)")
      .def("shows_between_branches", &Effect::shows_between_branches,
           "whether it shows only between the pressurising and venting branches of a supplied pressure")
      .def("reads_samples_alone", &Effect::reads_samples_alone,
           "whether what the instruments read at a sample depends on that sample alone (an offset, a gain), not on "
           "its neighbours (a lag, a skew)")
      .def("reads_supplied_pressure", &Effect::reads_supplied_pressure,
           "whether it is an error of the transducer whose reading drives a supplied test")
      .def(
          "apply_to_supplied_pressure",
          [](const Effect& e, const Array& time_s, const Array& gauge_pressure_Pa) {
            std::vector<double> pressure = vector(gauge_pressure_Pa);
            e.apply_to_supplied_pressure(vector(time_s), pressure);
            return copy(pressure);
          },
          py::arg("time_s"), py::arg("gauge_pressure_Pa"),
          "the gauge pressure [Pa] that drives a supplied test, from the reading (time_s empty: settled rows)")
      .def("apply_to_params",
           [](const Effect& e, MuscleParams params) {
             e.apply_to_params(params);
             return params;
           })
      .def(
          "apply_to_elongation",
          [](const Effect& e, const Array& time_s, const Array& crosshead_m) {
            return copy(e.apply_to_elongation(vector(time_s), vector(crosshead_m)));
          },
          py::arg("time_s"), py::arg("crosshead_m"), "the muscle's elongation [m] along the crosshead's, at time_s [s]")
      .def("apply_to_measurement",
           [](const Effect& e, Measurement measurement) {
             e.apply_to_measurement(measurement);
             return measurement;
           })
      .def("__repr__", [](const Effect& e) {
        std::string text = e.name() + "(";
        bool first = true;
        for (const auto& [key, value] : e.options()) {
          text += (first ? "" : ", ") + key + "=" + value;
          first = false;
        }
        for (const auto& p : e.parameters()) {
          text += (first ? "" : ", ") + p.name + "=" + std::to_string(p.value);
          first = false;
        }
        return text + ")";
      });

  py::class_<EffectCatalog>(m, "EffectCatalog", "Effect names mapped to factories.")
      .def(py::init<>())
      .def_static("builtin", &EffectCatalog::builtin, "the nine effects of the catalog")
      .def(
          "add",
          [](EffectCatalog& catalog, const std::string& name, const py::function& factory) {
            // A Python subclass's overrides live in its Python object: each effect made here
            // keeps that object alive as long as its C++ pointer lives, or the overrides
            // vanish as soon as the factory's result is dropped ("Tried to call pure virtual
            // function"). Both the factory and the kept objects are released under the GIL.
            const std::shared_ptr<py::function> shared(new py::function(factory), [](py::function* f) {
              py::gil_scoped_acquire gil;
              delete f;
            });
            catalog.add(name, [shared]() -> EffectPtr {
              py::gil_scoped_acquire gil;
              py::object made = (*shared)();
              Effect* effect = made.cast<Effect*>();
              auto* keep = new py::object(std::move(made));
              return EffectPtr(effect, [keep](Effect*) {
                py::gil_scoped_acquire release_gil;
                delete keep;
              });
            });
          },
          py::arg("name"), py::arg("factory"),
          "adds a factory (e.g. a pamkit.Effect subclass) called with no arguments for each new effect")
      .def("make", &EffectCatalog::make, py::arg("name"))
      .def("parse", &EffectCatalog::parse, py::arg("spec"), "'NAME' or 'NAME:key=value,...'")
      .def_static("split", &EffectCatalog::split, py::arg("spec"),
                  "the name and the (key, value) settings of a spec, as parse reads them, without making the effect")
      .def("names", &EffectCatalog::names);

  m.def("simulate_measurement", &simulate_measurement, py::arg("params"), py::arg("initial"), py::arg("crosshead"),
        py::arg("effects"), py::arg("simulator") = Simulator(), py::arg("shapes") = nullptr,
        py::call_guard<py::gil_scoped_release>(),
        "Simulates a sealed test as its instruments read it, with the effects applied at every stage. Releases "
        "the GIL: diagnosis fits run in parallel threads (a Python effect takes the GIL for its own calls). "
        "shapes: a ShapeTable of the build along the muscle's motion (ShapeTable(params, initial.length_m, "
        "crosshead) when no effect moves the muscle), read where it applies to the run (the effects leave the "
        "build, the motion and the fibres' stiffness as it has them), with the same result bit for bit; ignored "
        "otherwise (statistics.tabulated_shapes says which).");
  m.def(
      "simulate_measurement_blocks",
      [](const MuscleParams& params, const InitialState& initial, const ElongationTrajectory& crosshead,
         const std::vector<EffectPtr>& effects, const Simulator& simulator, std::size_t block_rows,
         const py::function& sink, const ShapeTable* shapes) {
        py::gil_scoped_release release;
        return simulate_measurement_blocks(
            params, initial, crosshead, effects, simulator, block_rows,
            [&sink](std::size_t first, const Measurement& block) {
              py::gil_scoped_acquire gil;
              py::dict channels;
              channels["time_s"] = copy(block.time_s);
              channels["elongation_m"] = copy(block.elongation_m);
              channels["force_N"] = copy(block.force_N);
              channels["gauge_pressure_Pa"] = copy(block.gauge_pressure_Pa);
              channels["temperature_K"] = copy(block.temperature_K);
              sink(first, channels);
            },
            shapes);
      },
      py::arg("params"), py::arg("initial"), py::arg("crosshead"), py::arg("effects"), py::arg("simulator"),
      py::arg("block_rows"), py::arg("sink"), py::arg("shapes") = nullptr,
      "simulate_measurement, its samples handed to sink(first, channels) as they are integrated, block_rows at a "
      "time: first is the index of the block's first sample, channels a dict of numpy arrays (time_s [s], "
      "elongation_m [m], force_N [N], gauge_pressure_Pa [Pa], temperature_K [K]). The samples equal "
      "simulate_measurement's bit for bit; only one block is held. Effects on the measured channels read the whole "
      "series and are refused (ValueError). Returns the SolverStatistics. Releases the GIL but for the sink's calls. "
      "shapes: as for simulate_measurement.");
  m.def(
      "simulate_supplied_measurement",
      [](const MuscleParams& params, double length_m, const ElongationTrajectory& crosshead,
         const Array& gauge_pressure_Pa, const std::vector<EffectPtr>& effects) {
        const std::vector<double> pressure = vector(gauge_pressure_Pa);
        py::gil_scoped_release release;
        return simulate_supplied_measurement(params, length_m, crosshead, pressure, effects);
      },
      py::arg("params"), py::arg("length_m"), py::arg("crosshead"), py::arg("gauge_pressure_Pa"), py::arg("effects"),
      "Simulates a supplied-pressure test: the measured gauge pressure [Pa] drives the static model at each "
      "sample of crosshead (lengths from length_m [m]), the gas at params.gas.ambient_temperature_K; force is "
      "predicted. Releases the GIL.");
  m.def(
      "static_forces",
      [](const MuscleParams& params, const Array& lengths_m, const Array& gauge_pressures_Pa,
         const std::vector<EffectPtr>& effects) {
        const std::vector<double> lengths = vector(lengths_m);
        const std::vector<double> pressures = vector(gauge_pressures_Pa);
        std::vector<double> force;
        {
          py::gil_scoped_release release;
          force = static_forces(params, lengths, pressures, effects);
        }
        return py::array_t<double>(static_cast<py::ssize_t>(force.size()), force.data());
      },
      py::arg("params"), py::arg("lengths_m"), py::arg("gauge_pressures_Pa"),
      py::arg("effects") = std::vector<EffectPtr>{},
      "The muscle's force at rest [N] at each row of a static table (length [m], supplied gauge pressure [Pa]), "
      "with physical effects applied. Releases the GIL.");
  py::class_<IsotonicLengths>(m, "IsotonicLengths", "Where an isotonic test's muscle settles at each row.")
      .def_property_readonly(
          "length_m",
          [](const IsotonicLengths& r) {
            return py::array_t<double>(static_cast<py::ssize_t>(r.length_m.size()), r.length_m.data());
          },
          "length at each row [m]")
      .def_property_readonly(
          "at_limit", [](const IsotonicLengths& r) { return std::vector<bool>(r.at_limit); },
          "whether each row's equilibrium lay beyond the range searched");
  m.def(
      "isotonic_lengths",
      [](const MuscleParams& params, const Array& gauge_pressures_Pa, double load_N, double start_length_m,
         const std::vector<EffectPtr>& effects) {
        const std::vector<double> pressures = vector(gauge_pressures_Pa);
        py::gil_scoped_release release;
        return isotonic_lengths(params, pressures, load_N, start_length_m, effects);
      },
      py::arg("params"), py::arg("gauge_pressures_Pa"), py::arg("load_N"), py::arg("start_length_m"),
      py::arg("effects") = std::vector<EffectPtr>{},
      "The length [m] at which the muscle carries load_N at each supplied gauge pressure [Pa], rows in the order "
      "measured, following the quasi-static path from start_length_m. Releases the GIL.");
  py::class_<IsotonicMotionConfig> motion_config(m, "IsotonicMotionConfig", "CVODES settings of isotonic_motion.");
  bind_fields(motion_config);
  py::class_<IsotonicMotion> motion(m, "IsotonicMotion",
                                    "A mass on the muscle over time, one entry per pressure sample.");
#define PAMKIT_MOTION_COLUMN(name, doc)                                                     \
  motion.def_property_readonly(                                                             \
      #name,                                                                                \
      [](const IsotonicMotion& r) {                                                         \
        return py::array_t<double>(static_cast<py::ssize_t>(r.name.size()), r.name.data()); \
      },                                                                                    \
      doc)
  PAMKIT_MOTION_COLUMN(time_s, "sample times [s]");
  PAMKIT_MOTION_COLUMN(length_m, "muscle length [m]");
  PAMKIT_MOTION_COLUMN(velocity_m_per_s, "lengthening rate [m/s], > 0 while the load wins");
  PAMKIT_MOTION_COLUMN(force_N, "the muscle's tension, friction included [N]");
  PAMKIT_MOTION_COLUMN(gauge_pressure_Pa, "gauge pressure that drove the model, effects applied [Pa]");
#undef PAMKIT_MOTION_COLUMN
  motion.def_readonly("statistics", &IsotonicMotion::statistics);
  m.def(
      "isotonic_motion",
      [](const MuscleParams& params, const Array& time_s, const Array& gauge_pressures_Pa, double load_N,
         double mass_kg, std::optional<double> start_length_m, const std::vector<EffectPtr>& effects,
         const IsotonicMotionConfig& config) {
        const std::vector<double> time = vector(time_s);
        const std::vector<double> pressures = vector(gauge_pressures_Pa);
        py::gil_scoped_release release;
        return isotonic_motion(params, time, pressures, load_N, mass_kg, start_length_m, effects, config);
      },
      py::arg("params"), py::arg("time_s"), py::arg("gauge_pressures_Pa"), py::arg("load_N"), py::arg("mass_kg"),
      py::arg("start_length_m") = py::none(), py::arg("effects") = std::vector<EffectPtr>{},
      py::arg("config") = IsotonicMotionConfig{},
      "Integrates a mass mass_kg [kg] under a constant load load_N [N] hanging on the muscle while the supplied "
      "gauge pressure [Pa] moves through its samples at time_s [s] (linear between them): m dv/dt = load - "
      "F(L, p, v), friction and effects included, starting at rest at start_length_m [m] (None: the quasi-static "
      "equilibrium of the first sample). Length and velocity at each sample. Releases the GIL.");
  m.def(
      "pressure_branches",
      [](const Array& gauge_pressure_Pa, double play_Pa) {
        const std::vector<double> branch = pressure_branches(vector(gauge_pressure_Pa), play_Pa);
        return py::array_t<double>(static_cast<py::ssize_t>(branch.size()), branch.data());
      },
      py::arg("gauge_pressure_Pa"), py::arg("play_Pa") = kPressureBranchPlay_Pa,
      "+1 where a supplied gauge pressure [Pa] is being raised, -1 where lowered (a play operator of half-width "
      "play_Pa [Pa]).");
  m.attr("PRESSURE_BRANCH_PLAY_PA") = kPressureBranchPlay_Pa;  // half the change that turns a branch [Pa]
}

}  // namespace pamkit::python
