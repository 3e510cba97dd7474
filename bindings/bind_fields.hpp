#pragma once
// Binds a parameter structure from its one field list (`for_each_field`): read-write
// attributes with unit and meaning in the docstring, keyword construction, `validate()`,
// `__repr__`, `to_dict()` and the class-level `fields()` that the file readers use.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <sstream>
#include <string>
#include <type_traits>

#include "pamkit/fields.hpp"

namespace pamkit::python {

namespace py = pybind11;

template <class Struct>
void bind_fields(py::class_<Struct>& cls) {
  Struct::for_each_field([&](const char* name, auto Struct::*member, const FieldInfo& info) {
    // An enumeration's range is its enumerators, which its Python type already lists.
    const bool enumerated = std::is_enum_v<std::remove_reference_t<decltype(std::declval<Struct&>().*member)>>;
    const std::string doc = enumerated ? std::string(info.description)
                                       : std::string(info.description) + " [" + info.unit + "], allowed [" +
                                             std::to_string(info.min) + ", " + std::to_string(info.max) + "]";
    cls.def_readwrite(name, member, doc.c_str());
  });
  cls.def(py::init([](const py::kwargs& kwargs) {
            Struct object;
            py::object handle = py::cast(&object, py::return_value_policy::reference);
            for (auto item : kwargs) {
              const auto key = item.first.cast<std::string>();
              if (!py::hasattr(py::type::of(handle), key.c_str())) {
                throw py::type_error(std::string(Struct::kName) + " has no field '" + key + "'");
              }
              handle.attr(key.c_str()) = item.second;
            }
            return object;
          }),
          "Keyword construction; fields not given keep their documented defaults.");
  cls.def("validate", &Struct::validate, "Raises ValueError naming the first field out of range.");
  cls.def_static(
      "fields",
      [] {
        py::dict out;
        Struct::for_each_field([&](const char* name, auto, const FieldInfo& info) {
          out[name] = py::dict(py::arg("unit") = info.unit, py::arg("min") = info.min, py::arg("max") = info.max,
                               py::arg("description") = info.description);
        });
        return out;
      },
      "Field names mapped to their unit, allowed range and meaning.");
  cls.def("to_dict", [](const Struct& s) {
    py::dict out;
    Struct::for_each_field([&](const char* name, auto Struct::*member, const FieldInfo&) { out[name] = s.*member; });
    return out;
  });
  cls.def("__repr__", [](const Struct& s) {
    std::ostringstream out;
    out.precision(10);
    out << Struct::kName << "(";
    bool first = true;
    Struct::for_each_field([&](const char* name, auto Struct::*member, const FieldInfo&) {
      out << (first ? "" : ", ") << name << "=" << s.*member;
      first = false;
    });
    out << ")";
    return out.str();
  });
}

}  // namespace pamkit::python
