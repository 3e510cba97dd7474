// Bindings of include/pamkit/effects: the Effect interface (subclassable from Python), the
// built-in catalog, and the simulated measurement.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/functional.h>

#include "pamkit/effects/catalog.hpp"
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
  void set(const std::string& key, const std::string& value) override { PYBIND11_OVERRIDE_PURE(void, Effect, set, key, value); }
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
  std::vector<double> apply_to_elongation(const std::vector<double>& time_s, const std::vector<double>& crosshead_m) const override {
    PYBIND11_OVERRIDE(std::vector<double>, Effect, apply_to_elongation, time_s, crosshead_m);
  }
  void apply_to_measurement(Measurement& measurement) const override {
    py::gil_scoped_acquire gil;
    py::function override = py::get_override(static_cast<const Effect*>(this), "apply_to_measurement");
    if (override) measurement = override(measurement).cast<Measurement>();
  }
};

py::array_t<double> copy(const std::vector<double>& v) { return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data()); }
std::vector<double> vector(const py::array_t<double, py::array::c_style | py::array::forcecast>& a) {
  return {a.data(), a.data() + a.size()};
}

}  // namespace

void bind_effects(py::module_& m) {
  py::enum_<GasMode>(m, "GasMode", "How the muscle's gas is held during a test.")
      .value("sealed", GasMode::sealed)
      .value("supplied", GasMode::supplied);

  py::class_<Measurement>(m, "Measurement", "Channels of a bench test on one time base (numpy arrays, copied in and out).")
      .def(py::init<>())
#define PAMKIT_CHANNEL(name, doc)                                                                        \
  def_property(#name, [](const Measurement& s) { return copy(s.name); },                                 \
               [](Measurement& s, const py::array_t<double, py::array::c_style | py::array::forcecast>& a) { \
                 s.name = vector(a);                                                                     \
               }, doc)
      .PAMKIT_CHANNEL(time_s, "sample times [s]")
      .PAMKIT_CHANNEL(elongation_m, "the crosshead's elongation [m]")
      .PAMKIT_CHANNEL(force_N, "load cell [N]")
      .PAMKIT_CHANNEL(pressure_kPa, "pressure transducer, gauge [kPa]")
      .PAMKIT_CHANNEL(temperature_C, "gas temperature sensor [degC]");
#undef PAMKIT_CHANNEL
  m.def("measured_channels", &measured_channels, "names of the channels effects may act on");

  py::class_<EffectParameter>(m, "EffectParameter", "One parameter of an effect.")
      .def(py::init<std::string, double, std::string, double, double, double, double, std::string>(), py::arg("name"),
           py::arg("value"), py::arg("unit"), py::arg("min"), py::arg("max"), py::arg("realistic_min"),
           py::arg("realistic_max"), py::arg("description") = "")
      .def_readonly("name", &EffectParameter::name)
      .def_readonly("value", &EffectParameter::value)
      .def_readonly("unit", &EffectParameter::unit)
      .def_readonly("min", &EffectParameter::min)
      .def_readonly("max", &EffectParameter::max)
      .def_readonly("realistic_min", &EffectParameter::realistic_min)
      .def_readonly("realistic_max", &EffectParameter::realistic_max)
      .def_readonly("description", &EffectParameter::description)
      .def("__repr__", [](const EffectParameter& p) { return p.name + "=" + std::to_string(p.value) + " " + p.unit; });

  py::class_<Effect, PyEffect, EffectPtr>(m, "Effect", R"doc(A model extension with physical parameters.

Subclass it in Python to add an effect: define name(), description(), parameters() (a list of
EffectParameter), set(key, value), and any of apply_to_params(params) -> params,
apply_to_elongation(time_s, crosshead_m) -> list, apply_to_measurement(measurement) -> measurement,
why_not(mode) -> None or a reason it cannot act in "sealed"/"supplied" tests.)doc")
      .def(py::init<>())
      .def("name", &Effect::name)
      .def("description", &Effect::description)
      .def("parameters", &Effect::parameters)
      .def("options", &Effect::options)
      .def("set", &Effect::set, py::arg("key"), py::arg("value"))
      .def("acts_in", [](const Effect& e, GasMode mode) {
             std::string why;
             const bool ok = e.acts_in(mode, &why);
             return py::make_tuple(ok, ok ? py::none() : py::cast(why));
           }, py::arg("mode"), "(True, None) or (False, reason)")
      .def("apply_to_params", [](const Effect& e, MuscleParams params) {
             e.apply_to_params(params);
             return params;
           })
      .def("apply_to_elongation", &Effect::apply_to_elongation, py::arg("time_s"), py::arg("crosshead_m"))
      .def("apply_to_measurement", [](const Effect& e, Measurement measurement) {
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
      .def("add", [](EffectCatalog& catalog, const std::string& name, const py::function& factory) {
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
           }, py::arg("name"), py::arg("factory"),
           "adds a factory (e.g. a pamkit.Effect subclass) called with no arguments for each new effect")
      .def("make", &EffectCatalog::make, py::arg("name"))
      .def("parse", &EffectCatalog::parse, py::arg("spec"), "'NAME' or 'NAME:key=value,...'")
      .def("names", &EffectCatalog::names);

  m.def("simulate_measurement", &simulate_measurement, py::arg("params"), py::arg("initial"), py::arg("crosshead"),
        py::arg("effects"), py::arg("simulator") = Simulator(),
        "Simulates a sealed test as its instruments read it, with the effects applied at every stage.");
}

}  // namespace pamkit::python
