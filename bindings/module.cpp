// The pamkit._core extension: one binding file per area, this file only assembles them and
// maps pamkit's exceptions to Python ones.

#include <pybind11/pybind11.h>

#include "pamkit/error.hpp"
#include "pamkit/units.hpp"
#include "pamkit/version.hpp"

namespace py = pybind11;

namespace pamkit::python {
void bind_muscle(py::module_& m);
void bind_gas(py::module_& m);
void bind_sim(py::module_& m);
void bind_effects(py::module_& m);
void bind_exo(py::module_& m);
void bind_logger(py::module_& m);
void bind_io(py::module_& m);
}  // namespace pamkit::python

PYBIND11_MODULE(_core, m) {
  m.doc() = "pamkit's compiled core: the muscle model of the thesis and its CVODES simulator (SI units).";
  m.attr("__version__") = PAMKIT_VERSION_STRING;  // CMakeLists.txt's project(VERSION), the one place it is kept
  // Bad parameters and inputs are ValueErrors; a failed integration is a RuntimeError.
  // pybind11 tries the most recently registered translator first, so the base class goes first.
  py::register_exception<pamkit::Error>(m, "Error", PyExc_RuntimeError);
  py::register_exception<pamkit::SolverError>(m, "SolverError", PyExc_RuntimeError);
  py::register_exception<pamkit::InvalidInput>(m, "InvalidInput", PyExc_ValueError);
  py::register_exception<pamkit::InvalidParameter>(m, "InvalidParameter", PyExc_ValueError);
  pamkit::python::bind_muscle(m);
  pamkit::python::bind_gas(m);
  pamkit::python::bind_sim(m);
  pamkit::python::bind_effects(m);
  pamkit::python::bind_exo(m);
  pamkit::python::bind_logger(m);
  pamkit::python::bind_io(m);

  py::module_ units =
      m.def_submodule("units", "Conversions for quantities that cross a boundary in other units (units.hpp).");
  units.attr("PASCAL_PER_KILOPASCAL") = pamkit::units::kPascalPerKilopascal;
  units.attr("KILOPASCAL_PER_PSI") = pamkit::units::kKilopascalPerPsi;
  units.attr("KILOPASCAL_PER_BAR") = pamkit::units::kKilopascalPerBar;
  units.attr("NEWTON_PER_KILOGRAM_FORCE") = pamkit::units::kNewtonPerKilogramForce;
  units.attr("KELVIN_AT_ZERO_CELSIUS") = pamkit::units::kKelvinAtZeroCelsius;
  units.attr("MILLIMETRE_PER_METRE") = pamkit::units::kMillimetrePerMetre;
}
