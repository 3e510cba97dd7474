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
  py::enum_<Construction>(m, "Construction", "How the fibres and the membrane are put together.")
      .value("sleeve", Construction::sleeve, "a bladder inside a braided sleeve (the thesis's muscle)")
      .value("embedded", Construction::embedded, "fibres embedded in the membrane: the braid cannot push");
  py::class_<MuscleBuild> build(m, "MuscleBuild",
                                "The muscle as built and deflated (SI units; thesis tables 3.4, C.4).");
  bind_fields(build);
  build.def_readwrite("construction", &MuscleBuild::construction,
                      "sleeve (a bladder in a braided sleeve, the thesis's) or embedded (fibres in the membrane)");

  py::class_<BiaxialStress>(m, "BiaxialStress", "Stresses or tangent moduli of the bladder in its two directions [Pa].")
      .def_readonly("longitudinal", &BiaxialStress::longitudinal)
      .def_readonly("hoop", &BiaxialStress::hoop)
      .def("__repr__", [](const BiaxialStress& s) {
        return "BiaxialStress(longitudinal=" + py::repr(py::float_(s.longitudinal)).cast<std::string>() +
               ", hoop=" + py::repr(py::float_(s.hoop)).cast<std::string>() + ")";
      });

  py::class_<BladderLaw> law(m, "BladderLaw",
                             "The bladder's membrane law: the thesis's polynomials of each strain, or an "
                             "incompressible neo-Hookean membrane.");
  py::enum_<BladderLaw::Form>(law, "Form")
      .value("polynomial", BladderLaw::Form::polynomial)
      .value("neo_hookean", BladderLaw::Form::neo_hookean);
  law.def(py::init<>())
      .def_readwrite("form", &BladderLaw::form, "polynomial or neo_hookean")
      .def_readwrite("longitudinal_Pa", &BladderLaw::longitudinal_Pa, "coefficients c0..c6 of sigma_l(eps_l) [Pa]")
      .def_readwrite("hoop_Pa", &BladderLaw::hoop_Pa, "coefficients c0..c6 of sigma_h(eps_h) [Pa]")
      .def_readwrite("shear_modulus_Pa", &BladderLaw::shear_modulus_Pa, "neo-Hookean shear modulus mu [Pa]")
      .def_static("thesis", &BladderLaw::thesis, "Eqs. 3.1.12-3.1.13 (with the lost '+' of the eps^4 term restored).")
      .def_static("neo_hookean", &BladderLaw::neo_hookean, py::arg("shear_modulus_Pa"),
                  "An incompressible neo-Hookean membrane of shear modulus mu [Pa].")
      .def_static("none", &BladderLaw::none, "No bladder stress.")
      .def("stresses", &BladderLaw::stresses, py::arg("longitudinal_strain"), py::arg("hoop_strain"),
           "Engineering stresses [Pa] at the two strains.")
      .def("tangent_moduli", &BladderLaw::tangent_moduli, py::arg("longitudinal_strain"), py::arg("hoop_strain"),
           "d sigma / d eps [Pa] of each direction in its own strain.");

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
  m.def("deflated_braid_angle_deg", &deflated_braid_angle_deg, py::arg("build"),
        "Braid angle of the deflated build's cylinder [deg]: tan(theta) = pi n D / Lm.");
  m.def("fiber_revolutions_for_braid_angle", &fiber_revolutions_for_braid_angle, py::arg("build"),
        py::arg("braid_angle_deg"), "The fiber revolutions n that give the deflated build this braid angle [deg].");
  m.def("braid_tension", &braid_tension, py::arg("force_N"), py::arg("band_N"),
        "What a braid transmits of a gas-and-bladder force [N]: it cannot push (smooth over band_N).");
  m.def("free_inflation", &free_inflation, py::arg("geometry"), py::arg("bladder"), py::arg("atmospheric_pressure_Pa"),
        py::arg("gauge_pressure_Pa"), "Length and diameter of the unloaded muscle inflated to a gauge pressure.");
}

}  // namespace pamkit::python
