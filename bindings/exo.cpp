// Bindings of include/pamkit/exo: gait data, the device's linkage, clutch and springs, the
// device over the gait cycle, and the tensile-jig conversion. Series come back as read-only
// numpy arrays that view the C++ vectors (no copy).

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bind_fields.hpp"
#include "pamkit/exo/device.hpp"
#include "pamkit/exo/jig.hpp"
#include "pamkit/exo/spring.hpp"

namespace py = pybind11;

namespace pamkit::python {
namespace {

using namespace pamkit::exo;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// A read-only numpy view of `vector`, kept alive by `owner`.
template <class T>
py::array_t<T> view(const std::vector<T>& vector, py::handle owner) {
  py::array_t<T> array(static_cast<py::ssize_t>(vector.size()), vector.data(), owner);
  array.attr("setflags")(py::arg("write") = false);
  return array;
}

std::vector<double> to_vector(const Array& a, const char* name) {
  if (a.ndim() != 1)
    throw py::value_error(std::string(name) + " must be a 1-D array, got " + std::to_string(a.ndim()) + " dimensions");
  return {a.data(), a.data() + a.size()};
}

/// Binds a read-only numpy property `name` viewing the vector member `member`.
template <class Class, class T>
void column(py::class_<Class>& cls, const char* name, std::vector<T> Class::*member, const char* doc) {
  cls.def_property_readonly(
      name, [member](py::object self) { return view(self.cast<const Class&>().*member, self); }, doc);
}

/// run_device for one concrete spring type, so C++ springs run without calling back into Python.
template <class Spring>
void def_run_device(py::module_& m) {
  m.def(
      "run_device",
      [](const GaitCycle& cycle, const Linkage& linkage, const ClutchParams& clutch, const PlayParams& play,
         const Spring& spring, int strides,
         ClutchMode initial) { return run_device(cycle, linkage, clutch, play, spring, strides, initial); },
      py::arg("cycle"), py::arg("linkage"), py::arg("clutch"), py::arg("play"), py::arg("spring"),
      py::arg("strides") = 3, py::arg("initial") = ClutchMode::engaged,
      "The device over `strides` repeats of the gait cycle; returns the last stride (DeviceRun). `spring` is a "
      "LinearSpring, ThesisPolynomialSpring, PamStaticSpring or any callable force_N(elongation_m).");
}

}  // namespace

void bind_exo(py::module_& m) {
  m.attr("WINTER_SUBJECT_MASS_KG") = kWinterSubjectMass_kg;

  // Gait data.
  py::class_<GaitData> data(m, "GaitData", "Winter's gait data as printed in appendix G.3: one row per frame.");
  data.def(py::init([](const Array& frame, const Array& hip, const Array& leg, const Array& foot, const Array& moment,
                       double mass) {
             return GaitData(to_vector(frame, "frame"), to_vector(hip, "hip_deg"), to_vector(leg, "leg_deg"),
                             to_vector(foot, "foot_deg"), to_vector(moment, "ankle_moment_Nm"), mass);
           }),
           py::arg("frame"), py::arg("hip_deg"), py::arg("leg_deg"), py::arg("foot_deg"), py::arg("ankle_moment_Nm"),
           py::arg("subject_mass_kg") = kWinterSubjectMass_kg,
           "Columns of equal length (angles [deg], moment [N m] with Winter's sign: plantarflexor < 0).")
      .def("__len__", &GaitData::size)
      .def_property_readonly("subject_mass_kg", &GaitData::subject_mass_kg)
      .def("ankle_angle_deg", &GaitData::ankle_angle_deg, py::arg("row"),
           "shank strut to foot arm at a row (G.3 testangle) [deg]");
  for (const auto& [name, getter] :
       {std::pair{"frame", &GaitData::frame}, std::pair{"hip_deg", &GaitData::hip_deg},
        std::pair{"leg_deg", &GaitData::leg_deg}, std::pair{"foot_deg", &GaitData::foot_deg},
        std::pair{"ankle_moment_Nm", &GaitData::ankle_moment_Nm}}) {
    data.def_property_readonly(
        name, [getter = getter](py::object self) { return view((self.cast<const GaitData&>().*getter)(), self); });
  }
  m.def("winter_appendix_g3", &winter_appendix_g3,
        "Winter's walking data as appendix G.3 prints it (56.7 kg subject).");

  py::class_<GaitEvents>(m, "GaitEvents", "Gait events found in the data (frame numbers as printed).")
      .def_readonly("heel_strike_frame", &GaitEvents::heel_strike_frame)
      .def_readonly("toe_off_frame", &GaitEvents::toe_off_frame)
      .def_readonly("stride_frames", &GaitEvents::stride_frames)
      .def_property_readonly("stance_percent", &GaitEvents::stance_percent, "stance over stride [%]");
  m.def("detect_gait_events", &detect_gait_events, py::arg("data"),
        "Stride, heel strike and toe-off from the data alone.");

  py::class_<GaitCycle> cycle(m, "GaitCycle",
                              "One stride at evenly spaced percent of the gait cycle, 0 % at heel strike.");
  column(cycle, "percent", &GaitCycle::percent, "percent of the gait cycle [%]");
  column(cycle, "hip_deg", &GaitCycle::hip_deg, "thigh segment angle [deg]");
  column(cycle, "leg_deg", &GaitCycle::leg_deg, "shank segment angle [deg]");
  column(cycle, "foot_deg", &GaitCycle::foot_deg, "foot segment angle [deg]");
  column(cycle, "ankle_angle_deg", &GaitCycle::ankle_angle_deg, "shank strut to foot arm (G.3 testangle) [deg]");
  column(cycle, "moment_Nm", &GaitCycle::moment_Nm,
         "biological ankle moment, plantarflexor > 0, scaled to body_mass_kg [N m]");
  cycle.def_readonly("body_mass_kg", &GaitCycle::body_mass_kg)
      .def_readonly("toe_off_percent", &GaitCycle::toe_off_percent)
      .def("__len__", &GaitCycle::size);
  m.def("resample_cycle", &resample_cycle, py::arg("data"), py::arg("events"), py::arg("points"),
        py::arg("body_mass_kg"), "One stride resampled at `points` percents, the moment scaled to body_mass_kg.");
  m.def("with_ankle_range", &with_ankle_range, py::arg("cycle"), py::arg("range_deg"),
        "The cycle with its ankle angle's excursion scaled to range_deg about the middle of its range.");

  // Linkage.
  py::class_<LinkageParams> linkage_params(m, "LinkageParams",
                                           "Dimensions of the device (appendix G.3's as defaults).");
  bind_fields(linkage_params);
  py::class_<LinkagePose>(m, "LinkagePose",
                          "The linkage at one heel-bar angle (shank frame: x up the shank, y to the heel).")
      .def_readonly("heel_bar_angle_deg", &LinkagePose::heel_bar_angle_deg)
      .def_readonly("shank_anchor_x_m", &LinkagePose::shank_anchor_x_m)
      .def_readonly("shank_anchor_y_m", &LinkagePose::shank_anchor_y_m)
      .def_readonly("heel_anchor_x_m", &LinkagePose::heel_anchor_x_m)
      .def_readonly("heel_anchor_y_m", &LinkagePose::heel_anchor_y_m)
      .def_readonly("spring_length_m", &LinkagePose::spring_length_m)
      .def_readonly("moment_arm_m", &LinkagePose::moment_arm_m);
  py::class_<Linkage>(m, "Linkage", "The device's geometry. Immutable.")
      .def(py::init<const LinkageParams&>(), py::arg("params") = LinkageParams{})
      .def("pose", &Linkage::pose, py::arg("heel_bar_angle_deg"))
      .def("elongation", &Linkage::elongation, py::arg("heel_bar_angle_deg"), "beyond the block length [m]")
      .def("horizontal_lever_m", &Linkage::horizontal_lever_m, py::arg("heel_bar_angle_deg"), py::arg("leg_deg"),
           "G.3's momentarm(1,:): horizontal distance ankle to heel anchor [m]")
      .def_property_readonly("min_spring_length", &Linkage::min_spring_length, "spring length at the block [m]")
      .def_property_readonly("params", &Linkage::params);

  // Springs.
  py::class_<LinearSpring> linear(m, "LinearSpring", "F = k e (G.3's coil spring).");
  bind_fields(linear);
  linear.def("__call__", &LinearSpring::operator(), py::arg("elongation_m"));
  py::class_<ThesisPolynomialSpring>(m, "ThesisPolynomialSpring",
                                     "G.3's pamequation: 0.1687 (1000e)^2 + 0.127 (1000e) + 16.9 [N].")
      .def(py::init<>())
      .def("__call__", &ThesisPolynomialSpring::operator(), py::arg("elongation_m"));
  py::class_<PamStaticSpring>(m, "PamStaticSpring",
                              "The muscle as a static, sealed, polytropic spring (pamkit's force model).")
      .def(py::init<const MuscleBuild&, const BladderLaw&, const GasParams&, double, double, double, double>(),
           py::arg("build"), py::arg("bladder"), py::arg("gas"), py::arg("free_length_m"), py::arg("gauge_pressure_Pa"),
           py::arg("pretension_m") = 0.0, py::arg("polytropic_index") = 1.0)
      .def("__call__", &PamStaticSpring::operator(), py::arg("elongation_m"), "force [N] at spring elongation [m]")
      .def("gauge_pressure", &PamStaticSpring::gauge_pressure, py::arg("elongation_m"), "[Pa]")
      .def("muscle_length", &PamStaticSpring::muscle_length, py::arg("elongation_m"), "[m]");

  // Clutch.
  py::enum_<ClutchMode>(m, "ClutchMode", "Mode of the ratchet-and-pawl timing mechanism (section 4.4).")
      .value("disengaged", ClutchMode::disengaged)
      .value("engaging", ClutchMode::engaging)
      .value("engaged", ClutchMode::engaged)
      .value("releasing", ClutchMode::releasing);
  py::class_<ClutchParams> clutch_params(m, "ClutchParams",
                                         "Screw angles and switching travel of the timing mechanism.");
  bind_fields(clutch_params);
  py::class_<PlayParams> play_params(m, "PlayParams", "Play between leg and device: dead zone and compliance.");
  bind_fields(play_params);
  py::class_<Clutch>(m, "Clutch", "The timing mechanism as a hybrid state machine.")
      .def(py::init<const ClutchParams&, ClutchMode>(), py::arg("params"), py::arg("initial") = ClutchMode::engaged)
      .def("step", &Clutch::step, py::arg("device_angle_deg"))
      .def("stretch_deg", &Clutch::stretch_deg, py::arg("device_angle_deg"))
      .def_property_readonly("mode", &Clutch::mode)
      .def_property_readonly("reference_deg", &Clutch::reference_deg);

  m.def("fit_clutch", &fit_clutch, py::arg("cycle"), py::arg("travel_deg") = 7.0, py::arg("margin_deg") = 0.5,
        "Screw angles that engage before heel strike and release at push-off for this gait on a well-fitted device.");

  // The device over the gait cycle.
  py::class_<DeviceRun> run(m, "DeviceRun", "One stride of the device, per gait-cycle sample.");
  column(run, "percent", &DeviceRun::percent, "percent of the gait cycle [%]");
  column(run, "ankle_angle_deg", &DeviceRun::ankle_angle_deg, "leg's shank-to-foot angle [deg]");
  column(run, "device_angle_deg", &DeviceRun::device_angle_deg, "device's shank-to-foot angle after play [deg]");
  column(run, "mode", &DeviceRun::mode, "ClutchMode value per sample");
  column(run, "heel_bar_angle_deg", &DeviceRun::heel_bar_angle_deg, "heel bar to shank strut [deg]");
  column(run, "spring_length_m", &DeviceRun::spring_length_m, "anchor to anchor [m]");
  column(run, "elongation_m", &DeviceRun::elongation_m, "beyond the block length [m]");
  column(run, "moment_arm_m", &DeviceRun::moment_arm_m, "perpendicular moment arm [m]");
  column(run, "horizontal_lever_m", &DeviceRun::horizontal_lever_m, "G.3 momentarm(1,:) [m]");
  column(run, "force_N", &DeviceRun::force_N, "spring force [N]");
  column(run, "torque_Nm", &DeviceRun::torque_Nm, "plantarflexor torque of the device [N m]");
  column(run, "biological_torque_Nm", &DeviceRun::biological_torque_Nm, "biological ankle moment [N m]");
  run.def_readonly("engage_percent", &DeviceRun::engage_percent, "where the pawl meshed [%], or None")
      .def_readonly("release_percent", &DeviceRun::release_percent, "where the pawl lifted [%], or None");
  def_run_device<LinearSpring>(m);
  def_run_device<ThesisPolynomialSpring>(m);
  def_run_device<PamStaticSpring>(m);
  def_run_device<std::function<double(double)>>(m);

  py::class_<IdealSpring> ideal(m, "IdealSpring",
                                "The force that would give a share of the biological moment (figure 4.7).");
  column(ideal, "percent", &IdealSpring::percent, "stance samples with the spring stretched [%]");
  column(ideal, "elongation_m", &IdealSpring::elongation_m, "[m]");
  column(ideal, "force_N", &IdealSpring::force_N, "[N]");
  ideal.def_readonly("peak_force_N", &IdealSpring::peak_force_N)
      .def_readonly("elongation_at_peak_m", &IdealSpring::elongation_at_peak_m)
      .def_readonly("max_elongation_m", &IdealSpring::max_elongation_m)
      .def_readonly("loading_samples", &IdealSpring::loading_samples)
      .def("force_at", &IdealSpring::force_at, py::arg("elongation_m"),
           "force on the stretching branch [N], or None if never reached");
  m.def("ideal_spring", &ideal_spring, py::arg("run"), py::arg("toe_off_percent"), py::arg("share"));

  py::class_<ScriptKinematics> script(m, "ScriptKinematics", "Appendix G.3's script as printed, rows 2..83.");
  column(script, "row", &ScriptKinematics::row, "1-based data row");
  column(script, "spring_length_m", &ScriptKinematics::spring_length_m, "springlength [m]");
  column(script, "elongation_m", &ScriptKinematics::elongation_m, "elongation [m]");
  column(script, "moment_arm_m", &ScriptKinematics::moment_arm_m, "perpendicular moment arm [m]");
  column(script, "horizontal_lever_m", &ScriptKinematics::horizontal_lever_m, "momentarm(1,:) [m]");
  column(script, "moment_Nm", &ScriptKinematics::moment_Nm, "anklemoment, scaled [N m]");
  column(script, "ideal_force_N", &ScriptKinematics::ideal_force_N, "idealforce [N]");
  m.def("reproduce_g3_script", &reproduce_g3_script, py::arg("data"), py::arg("linkage"), py::arg("body_mass_kg"),
        py::arg("begin_row") = 12, py::arg("end_row") = 43, py::arg("ideal_rows") = 45);

  m.def("walking_trajectory", &walking_trajectory, py::arg("run"), py::arg("stride_period_s"), py::arg("strides"),
        py::arg("pretension_m") = 0.0, "The muscle's elongation over repeated strides, for the Simulator.");

  // The tensile jig of appendix G.4.
  py::class_<JigParams> jig_params(m, "JigParams", "Set-up of the exoskeleton in the Instron (appendix G.4).");
  bind_fields(jig_params);
  py::class_<JigSample>(m, "JigSample", "One converted crosshead sample.")
      .def_readonly("rotation_deg", &JigSample::rotation_deg)
      .def_readonly("heel_bar_angle_deg", &JigSample::heel_bar_angle_deg)
      .def_readonly("muscle_length_m", &JigSample::muscle_length_m)
      .def_readonly("muscle_force_N", &JigSample::muscle_force_N)
      .def_readonly("ankle_moment_Nm", &JigSample::ankle_moment_Nm);
  py::class_<Jig>(m, "Jig", "Crosshead displacement and force to muscle length, force and ankle moment.")
      .def(py::init<const LinkageParams&, const JigParams&>(), py::arg("linkage") = LinkageParams{},
           py::arg("jig") = JigParams{})
      .def("convert", &Jig::convert, py::arg("displacement_m"), py::arg("force_N"))
      .def_property_readonly("linkage", &Jig::linkage)
      .def_property_readonly("params", &Jig::params);
  py::class_<Table42Row>(m, "Table42Row", "A row of table 4.2.")
      .def_readonly("gauge_pressure_Pa", &Table42Row::gauge_pressure_Pa)
      .def_readonly("muscle_length_m", &Table42Row::muscle_length_m)
      .def_readonly("angle_deg", &Table42Row::angle_deg)
      .def_readonly("vertical_displacement_m", &Table42Row::vertical_displacement_m);
  m.def("table_4_2", &table_4_2, "Table 4.2 as printed.");
}

}  // namespace pamkit::python
