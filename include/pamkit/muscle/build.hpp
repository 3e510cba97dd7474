#pragma once
/// \file
/// The muscle as built: dimensions measured on the deflated muscle, and the braid.

#include "pamkit/fields.hpp"

namespace pamkit {

/// How the fibres and the membrane are put together.
enum class Construction {
  /// A bladder inside a braided sleeve (the thesis's muscle): the thesis's model, whose braid
  /// pushes as readily as it pulls.
  sleeve,
  /// Fibres embedded in the membrane (a Festo fluidic muscle): no bladder-braid gap, and a braid
  /// that cannot push. Held shorter than its free length the muscle goes slack and carries
  /// nothing: the force passes through `braid_tension` (muscle/force.hpp) in every prediction.
  embedded
};

/// The name a file gives a construction ("sleeve", "embedded").
inline const char* to_string(Construction construction) {
  return construction == Construction::sleeve ? "sleeve" : "embedded";
}

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
  double end_zone_m = 0.0;  ///< flat ends: length of braid at each flange that keeps its deflated shape [m]; 0 = none
  Construction construction = Construction::sleeve;  ///< fibres in a sleeve (thesis) or in the membrane
  /// what stretches in series with the braid between the points whose distance a rig holds or
  /// measures (fittings, load cell, frame) per newton of the muscle's pull [m/N]; 0 = rigid
  double series_compliance_m_per_N = 0.0;

  // Note on end_zone_m: pressed onto a flat flange, the braid cannot reach its cylinder's diameter
  // near the flange. Tondu and Lopez (2000) correct Gaylord's force for it by contracting the
  // muscle k = L0 / (L0 - 2 e) times faster; here each end zone keeps its deflated diameter and
  // length (it neither contracts nor changes volume), and the braid between them is the cylinder
  // of the thesis. The two published Festo maps give e = 0.7-0.9 braid diameters
  // (data/experiments/festo).
  //
  // The construction is not in the field list below (a field list of numbers): the experiment
  // reader and the muscle-parameters file read it by name, `construction = "embedded"`.

  // Note on series_compliance_m_per_N: a held muscle's braid lies short of the held length by what
  // its pull stretches the parts in series with it, L_braid = L - c F, and its slip elements follow
  // that motion. Where the force is steep in the length (near rest, at high pressure) this lowers
  // the force most: the published DMSP-10-250 map calibrates c = 4.5 um/N (220 N/mm, a bench's
  // fittings and load cell), the DMSP-20-300's none within its interval. Modelled where the muscle
  // settles at each row or sample (static tables, supplied tests, the real-time force); a sealed
  // test's ODE refuses it.

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
    visit("end_zone_m", &MuscleBuild::end_zone_m,
          FieldInfo{"m", 0.0, 0.5, "flat ends: braid at each flange that keeps its deflated shape (0: none)"});
    visit("series_compliance_m_per_N", &MuscleBuild::series_compliance_m_per_N,
          FieldInfo{"m/N", 0.0, 1e-3,
                    "stretch in series with the braid per newton of pull, in tables and supplied tests (0: rigid)"});
  }

  /// Checks each field's range, then the relations between fields (the bladder fits inside
  /// the braid, the end caps are narrower than the braid, the cones or the end zones fit in the
  /// length, end zones only with flat ends).
  /// \throws InvalidParameter naming the field.
  void validate() const;
};

}  // namespace pamkit

#include "pamkit/muscle/build.hxx"
