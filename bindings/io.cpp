// Bindings of include/pamkit/io: the muscle-parameters file (TOML under the C++ field names).

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "pamkit/io/params_file.hpp"

namespace py = pybind11;

namespace pamkit::python {

void bind_io(py::module_& m) {
  py::class_<MuscleParamsFile>(m, "MuscleParamsFile", "What a muscle-parameters file holds.")
      .def_readonly("params", &MuscleParamsFile::params,
                    "the muscle: [build], [bladder], [friction], [gas], [extensions]")
      .def_readonly("initial", &MuscleParamsFile::initial,
                    "[initial]: the state at zero elongation of the sealed test the parameters were calibrated on, "
                    "or None")
      .def_readonly("rig_effects", &MuscleParamsFile::rig_effects,
                    "[rig] effects: what a diagnosis found in the test's fixture and instruments, as effect specs "
                    "(\"NAME:key=value,...\"); empty if the file has none");

  m.def(
      "read_muscle_params_file",
      [](const std::filesystem::path& path) { return read_muscle_params_file(path.string()); }, py::arg("path"),
      "Reads and validates a muscle-parameters TOML file: its MuscleParams and its optional [initial] state. "
      "Raises ValueError naming the file, line, column and key (unknown or missing section or key, wrong type, "
      "a value outside its field's range).");
  m.def(
      "read_muscle_params", [](const std::filesystem::path& path) { return read_muscle_params(path.string()); },
      py::arg("path"), "The MuscleParams of a muscle-parameters TOML file (read_muscle_params_file(path).params).");
  m.def(
      "write_muscle_params",
      [](const std::filesystem::path& path, const MuscleParams& params, const std::optional<InitialState>& initial,
         const std::string& comment, const std::vector<std::string>& rig_effects) {
        write_muscle_params(path.string(), params, initial, comment, rig_effects);
      },
      py::arg("path"), py::arg("params"), py::arg("initial") = py::none(), py::arg("comment") = "",
      py::arg("rig_effects") = std::vector<std::string>{},
      "Writes params (validated first) and, if given, the initial state as a muscle-parameters TOML file under the "
      "C++ field names, each key with its unit and meaning; `comment` goes at the top as TOML comments; "
      "`rig_effects` (effect specs of the test's fixture and instruments) as [rig] effects. "
      "read_muscle_params gives back the same doubles.");
}

}  // namespace pamkit::python
