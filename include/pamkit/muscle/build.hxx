#pragma once

namespace pamkit {

inline void MuscleBuild::validate() const {
  validate_fields(*this);
  if (construction != Construction::sleeve && construction != Construction::embedded) {
    PAMKIT_THROW(InvalidParameter(detail::message("MuscleBuild.construction = ", static_cast<int>(construction),
                                                  " is neither sleeve nor embedded")));
  }
  if (end_zone_m > 0.0 && cone_generator_m > 0.0) {
    PAMKIT_THROW(InvalidParameter(detail::message(
        "MuscleBuild.end_zone_m = ", end_zone_m, " m with cone_generator_m = ", cone_generator_m,
        " m: end zones belong to flat flanges; the thesis's cones are their own end model (give one)")));
  }
  if (2.0 * end_zone_m >= length_m) {
    PAMKIT_THROW(InvalidParameter(detail::message("MuscleBuild.end_zone_m = ", end_zone_m,
                                                  " m: two end zones do not fit in length_m = ", length_m, " m")));
  }
  if (bladder_diameter_m > diameter_m) {
    PAMKIT_THROW(InvalidParameter(detail::message("MuscleBuild.bladder_diameter_m = ", bladder_diameter_m,
                                                  " m is larger than the braid diameter_m = ", diameter_m,
                                                  " m: the bladder must fit inside the braid")));
  }
  if (2.0 * (bladder_thickness_m + fiber_thickness_m) >= bladder_diameter_m) {
    PAMKIT_THROW(InvalidParameter(detail::message(
        "MuscleBuild.bladder_thickness_m = ", bladder_thickness_m, " m and fiber_thickness_m = ", fiber_thickness_m,
        " m leave no gas space in a bladder of diameter ", bladder_diameter_m, " m")));
  }
  if (cone_generator_m > 0.0) {
    if (end_diameter_m >= diameter_m) {
      PAMKIT_THROW(InvalidParameter(detail::message("MuscleBuild.end_diameter_m = ", end_diameter_m,
                                                    " m must be smaller than diameter_m = ", diameter_m,
                                                    " m (the end cones narrow from the braid to the cap)")));
    }
    if (diameter_m - end_diameter_m >= 2.0 * cone_generator_m) {
      PAMKIT_THROW(InvalidParameter(detail::message("MuscleBuild.cone_generator_m = ", cone_generator_m,
                                                    " m is too short to join the braid diameter ", diameter_m,
                                                    " m to the end diameter ", end_diameter_m, " m (needs more than ",
                                                    0.5 * (diameter_m - end_diameter_m), " m)")));
    }
    if (2.0 * cone_generator_m >= length_m) {
      PAMKIT_THROW(InvalidParameter(detail::message("MuscleBuild.cone_generator_m = ", cone_generator_m,
                                                    " m: two cones do not fit in length_m = ", length_m, " m")));
    }
  }
}

}  // namespace pamkit
