// Bindings of include/pamkit/muscle: the build, braid geometry, bladder, friction, forces and
// free inflation.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bind_fields.hpp"
#include "pamkit/muscle/free_inflation.hpp"

namespace py = pybind11;

namespace pamkit::python {

void bind_muscle(py::module_& m) {
  py::class_<MuscleBuild> build(m, "MuscleBuild",
                                "The muscle as built and deflated (SI units; thesis tables 3.4, C.4).");
  bind_fields(build);

  py::class_<BladderLaw>(m, "BladderLaw",
                         "Biaxial bladder stress law: polynomials c0..c6 [Pa] of the strain in each direction.")
      .def(py::init<>())
      .def_readwrite("longitudinal_Pa", &BladderLaw::longitudinal_Pa, "coefficients c0..c6 of sigma_l(eps_l) [Pa]")
      .def_readwrite("hoop_Pa", &BladderLaw::hoop_Pa, "coefficients c0..c6 of sigma_h(eps_h) [Pa]")
      .def_static("thesis", &BladderLaw::thesis, "Eqs. 3.1.12-3.1.13 (with the lost '+' of the eps^4 term restored).")
      .def_static("none", &BladderLaw::none, "No bladder stress.")
      .def("longitudinal_stress", py::vectorize(&BladderLaw::longitudinal_stress), py::arg("strain"),
           "sigma_l [Pa] at longitudinal strain (scalar or array)")
      .def("hoop_stress", py::vectorize(&BladderLaw::hoop_stress), py::arg("strain"),
           "sigma_h [Pa] at hoop strain (scalar or array)");

  py::class_<FrictionParams> friction(m, "FrictionParams",
                                      "Fiber-fiber and fiber-bladder friction (eqs. 3.1.19-3.1.24).");
  bind_fields(friction);

  py::class_<MuscleShape>(m, "MuscleShape", "Shape of the muscle at one length (SI units, angles in rad).")
      .def_readonly("length", &MuscleShape::length)
      .def_readonly("diameter", &MuscleShape::diameter)
      .def_readonly("cylinder_length", &MuscleShape::cylinder_length)
      .def_readonly("cone_length", &MuscleShape::cone_length)
      .def_readonly("braid_angle", &MuscleShape::braid_angle)
      .def_readonly("end_braid_angle", &MuscleShape::end_braid_angle)
      .def_readonly("cone_angle", &MuscleShape::cone_angle)
      .def_readonly("mean_braid_angle", &MuscleShape::mean_braid_angle)
      .def_readonly("total_volume", &MuscleShape::total_volume)
      .def_readonly("bladder_volume", &MuscleShape::bladder_volume)
      .def_readonly("gas_volume", &MuscleShape::gas_volume)
      .def_readonly("d_diameter", &MuscleShape::d_diameter)
      .def_readonly("d_cylinder_length", &MuscleShape::d_cylinder_length)
      .def_readonly("d_total_volume", &MuscleShape::d_total_volume)
      .def_readonly("d_bladder_volume", &MuscleShape::d_bladder_volume)
      .def_readonly("d_gas_volume", &MuscleShape::d_gas_volume);

  py::class_<BraidGeometry>(m, "BraidGeometry",
                            "Braid kinematics and volumes of one build (eqs. 3.1.1-3.1.3, 3.1.9-3.1.11).")
      .def(py::init<const MuscleBuild&>(), py::arg("build"))
      .def("shape", &BraidGeometry::shape, py::arg("length_m"), "Shape at muscle length [m].")
      .def_property_readonly("min_length", &BraidGeometry::min_length, "shortest allowed length [m]")
      .def_property_readonly("max_length", &BraidGeometry::max_length, "longest allowed length [m]")
      .def_property_readonly("fiber_length", &BraidGeometry::fiber_length, "fiber length over the cylinder Lym [m]")
      .def_property_readonly("deflated_cylinder_length", &BraidGeometry::deflated_cylinder_length,
                             "cylinder length of the deflated build [m]")
      .def_property_readonly("build", &BraidGeometry::build);

  m.def("braid_diameter", &braid_diameter, py::arg("fiber_length_m"), py::arg("revolutions"),
        py::arg("braid_angle_rad"), "Eq. 3.1.9: D = Lym sin(theta) / (pi n) [m].");
  m.def("braid_cylinder_length", &braid_cylinder_length, py::arg("fiber_length_m"), py::arg("braid_angle_rad"),
        "Eq. 3.1.10: Lm = Lym cos(theta) [m].");
  m.def("braid_fiber_length", &braid_fiber_length, py::arg("cylinder_length_m"), py::arg("diameter_m"),
        py::arg("revolutions"), "Eq. 3.1.11 solved for Lym [m].");

  py::class_<MuscleForces>(m, "MuscleForces", "Axial force and its parts [N], tension > 0.")
      .def_readonly("pressure", &MuscleForces::pressure)
      .def_readonly("bladder", &MuscleForces::bladder)
      .def_readonly("friction", &MuscleForces::friction)
      .def_readonly("total", &MuscleForces::total);
  m.def("muscle_forces", &muscle_forces, py::arg("geometry"), py::arg("shape"), py::arg("bladder"), py::arg("friction"),
        py::arg("absolute_pressure_Pa"), py::arg("atmospheric_pressure_Pa"), py::arg("velocity_m_per_s"),
        "Virtual-work force of gas and bladder plus friction at one shape.");

  py::class_<FiberTensions>(m, "FiberTensions",
                            "Fiber tensions of the Newtonian model [N per fiber] and its force [N].")
      .def_readonly("cylinder_hoop", &FiberTensions::cylinder_hoop)
      .def_readonly("cone_hoop", &FiberTensions::cone_hoop)
      .def_readonly("longitudinal", &FiberTensions::longitudinal)
      .def_readonly("force", &FiberTensions::force);
  m.def("newtonian_fiber_tensions", &newtonian_fiber_tensions, py::arg("geometry"), py::arg("shape"),
        py::arg("bladder"), py::arg("gauge_pressure_Pa"),
        "The thesis's Newtonian fiber tensions and force (eqs. 3.1.4-3.1.8).");

  py::class_<FreeInflation>(m, "FreeInflation", "Free (zero-force) length and diameter after inflation.")
      .def_readonly("length_m", &FreeInflation::length_m)
      .def_readonly("diameter_m", &FreeInflation::diameter_m)
      .def_readonly("contracted", &FreeInflation::contracted)
      .def("__repr__", [](const FreeInflation& f) {
        return "FreeInflation(length_m=" + std::to_string(f.length_m) + ", diameter_m=" + std::to_string(f.diameter_m) +
               ", contracted=" + (f.contracted ? "True" : "False") + ")";
      });
  m.def("free_inflation", &free_inflation, py::arg("geometry"), py::arg("bladder"), py::arg("atmospheric_pressure_Pa"),
        py::arg("gauge_pressure_Pa"), "Length and diameter of the unloaded muscle inflated to a gauge pressure.");
}

}  // namespace pamkit::python
