#pragma once
/// \file
/// The muscle as built: dimensions measured on the deflated muscle, and the braid.

#include "pamkit/fields.hpp"

namespace pamkit {

/// The muscle as built and deflated (thesis section 3.2, tables 3.4 and C.4). The defaults
/// are PAM 2 of table 3.4, the muscle of the high-pressure tests.
struct MuscleBuild {
  static constexpr const char* kName = "MuscleBuild";

  double length_m = 0.225;                ///< deflated length between the end caps [m] (table 3.4, PAM 2)
  double diameter_m = 0.020;              ///< deflated braid diameter [m] (table 3.4; Dref, table C.4)
  double bladder_diameter_m = 0.01545;    ///< deflated bladder outer diameter [m] (Dbo, table C.4)
  double bladder_thickness_m = 0.254e-3;  ///< bladder wall thickness [m] (tb, table C.4; see note)
  double fiber_count = 216;               ///< number of braid fibers N [1] (table C.4)
  double fiber_revolutions = 2;           ///< full turns n of each fiber over the cylinder [1] (table C.4)
  double fiber_thickness_m = 0.254e-3;    ///< thickness of one fiber tf [m] (table C.4)
  double end_diameter_m = 0.013;          ///< diameter d of the end caps [m] (Dend, table C.4)
  double cone_generator_m = 0.0095;       ///< slant length Lz of each end cone [m] (table C.4); 0 = flat ends

  // Note on bladder_thickness_m: section 3.1.2 measured the butyl tube at 0.9 mm, table C.4
  // ran the model with 0.254 mm. With the stress laws of eqs. 3.1.12-13 a 0.9 mm bladder
  // resists inflation more than 35-104 kPa can overcome (tests/cpp/free_inflation.test.cpp
  // shows it); 0.254 mm reproduces table 3.4, so it is the default.

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("length_m", &MuscleBuild::length_m, FieldInfo{"m", 0.01, 5.0, "deflated length between the end caps"});
    visit("diameter_m", &MuscleBuild::diameter_m, FieldInfo{"m", 1e-3, 0.5, "deflated braid diameter"});
    visit("bladder_diameter_m", &MuscleBuild::bladder_diameter_m,
          FieldInfo{"m", 1e-3, 0.5, "deflated bladder outer diameter"});
    visit("bladder_thickness_m", &MuscleBuild::bladder_thickness_m,
          FieldInfo{"m", 0.0, 0.01, "bladder wall thickness"});
    visit("fiber_count", &MuscleBuild::fiber_count, FieldInfo{"1", 2, 5000, "number of braid fibers N"});
    visit("fiber_revolutions", &MuscleBuild::fiber_revolutions,
          FieldInfo{"1", 0.1, 100, "fiber turns n over the cylinder"});
    visit("fiber_thickness_m", &MuscleBuild::fiber_thickness_m, FieldInfo{"m", 0.0, 0.01, "thickness of one fiber"});
    visit("end_diameter_m", &MuscleBuild::end_diameter_m, FieldInfo{"m", 1e-4, 0.5, "end cap diameter d"});
    visit("cone_generator_m", &MuscleBuild::cone_generator_m,
          FieldInfo{"m", 0.0, 0.5, "slant length of each end cone Lz (0: flat ends)"});
  }

  /// Checks each field's range, then the relations between fields (the bladder fits inside
  /// the braid, the end caps are narrower than the braid, the cones fit in the length).
  /// \throws InvalidParameter naming the field.
  void validate() const;
};

}  // namespace pamkit

#include "pamkit/muscle/build.hxx"
