// Bindings of include/pamkit/gas: air properties, the gas process, the polytropic closed forms.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "bind_fields.hpp"
#include "pamkit/gas/air.hpp"

namespace py = pybind11;

namespace pamkit::python {

void bind_gas(py::module_& m) {
  py::enum_<GasProcess>(m, "GasProcess", "How the gas exchanges heat with the wall.")
      .value("polytropic", GasProcess::polytropic, "p V^n = const (eq. 3.1.14)")
      .value("heat_transfer", GasProcess::heat_transfer, "energy balance with gas-wall exchange, time constant tau");

  py::class_<GasParams> gas(m, "GasParams", "Air, ambient conditions and the gas process (SI units).");
  bind_fields(gas);
  gas.def_readwrite("process", &GasParams::process, "GasProcess: polytropic or heat_transfer");
  gas.def_property_readonly("specific_heat_cv", &GasParams::specific_heat_cv, "cv = R / (gamma - 1) [J/(kg K)]");

  m.def("polytropic_pressure", py::vectorize(&polytropic_pressure), py::arg("p0_abs_Pa"), py::arg("v0_m3"),
        py::arg("v_m3"), py::arg("n"), "Eq. 3.1.16: absolute pressure after a polytropic change [Pa].");
  m.def("polytropic_temperature", py::vectorize(&polytropic_temperature), py::arg("t0_K"), py::arg("v0_m3"),
        py::arg("v_m3"), py::arg("n"), "Eq. 3.1.18: temperature after a polytropic change [K].");
}

}  // namespace pamkit::python
