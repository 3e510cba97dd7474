#pragma once
/// \file
/// Appendix G.4: the exoskeleton mounted in the Instron (section 4.6, figures 4.15-4.18), and
/// the conversion of the crosshead's displacement and force into muscle length, muscle force
/// and ankle moment.
///
/// Jig frame (figure 4.16): origin at the ankle joint, x horizontal, y up. The foot plate is
/// bolted down with the heel bar at alpha from the vertical (point B = Lh (cos(90 deg + alpha),
/// sin(90 deg + alpha))); the shank strut lies near the horizontal at beta = 90 deg + alpha -
/// theta, where theta is the angle between shank strut and heel bar; its end C = Ls (cos beta,
/// sin beta); the shank anchor A = C + Lo (cos(beta + 90 deg), sin(beta + 90 deg)). The
/// crosshead pushes the shank end down by d, turning the shank by asin(d / Ls).
///
/// Sign: pushing the shank end down lowers beta and so opens theta, which stretches the muscle
/// (figures 4.19 and 4.21 plot positive elongations). G.4 writes theta = thetao - deltatheta
/// after flipping the Instron's displacement sign; which sign its raw data had is not printed,
/// so here d > 0 is the crosshead descending and theta = thetao + asin(d / Ls).
/// theta plays the part of the heel-bar angle psi of the linkage (exo/linkage.hpp): the same
/// triangle, seen with the foot bolted down instead of the shank upright.

#include <cmath>
#include <vector>

#include "pamkit/exo/linkage.hpp"

namespace pamkit::exo {

/// The jig's set-up.
struct JigParams {
  static constexpr const char* kName = "JigParams";

  double heel_bar_tilt_deg = 5.0;  ///< alpha, heel bar from the vertical, kept constant [deg] (G.4 `alpha`, fig. 4.18)
  double initial_angle_deg =
      85.0;  ///< theta at zero displacement, shank strut to heel bar [deg] (G.4 `thetao`; table 4.2)

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("heel_bar_tilt_deg", &JigParams::heel_bar_tilt_deg,
          FieldInfo{"deg", -45.0, 45.0, "heel bar from vertical (G.4 alpha)"});
    visit("initial_angle_deg", &JigParams::initial_angle_deg,
          FieldInfo{"deg", 1.0, 179.0, "shank strut to heel bar at the start (G.4 thetao)"});
  }
  void validate() const { validate_fields(*this); }
};

/// One converted sample.
struct JigSample {
  double rotation_deg;        ///< shank rotation asin(d / Ls) [deg] (G.4 `deltatheta`)
  double heel_bar_angle_deg;  ///< theta = thetao + rotation [deg]
  double muscle_length_m;     ///< |A - B| [m] (G.4 `Lm`)
  double muscle_force_N;      ///< tension [N] (G.4 `Fm`)
  double ankle_moment_Nm;     ///< moment of the muscle about the ankle, plantarflexion > 0 [N m] (G.4 `Moment`)
};

/// The conversion. Immutable.
class Jig {
 public:
  /// The device's linkage gives Ls (upright length), Lo (shank offset) and Lh (heel offset).
  /// \throws InvalidParameter naming the field.
  Jig(const LinkageParams& linkage, const JigParams& jig)
      : linkage_((linkage.validate(), linkage)), jig_((jig.validate(), jig)) {}

  /// Converts the crosshead's downward displacement [m] and compressive force [N] (the
  /// script flips the Instron's signs and turns mm into m before this point).
  /// \throws InvalidInput if the displacement exceeds the upright (the link cannot close),
  ///         or the rotation turns theta out of (0, 180) deg.
  JigSample convert(double displacement_m, double force_N) const;

  const LinkageParams& linkage() const { return linkage_; }
  const JigParams& params() const { return jig_; }

 private:
  LinkageParams linkage_;
  JigParams jig_;
};

inline JigSample Jig::convert(double d, double force) const {
  const double ls = linkage_.upright_length_m;
  if (!std::isfinite(d) || std::abs(d) > ls) {
    throw InvalidInput(pamkit::detail::message("Jig: crosshead displacement ", d, " m exceeds upright_length_m = ", ls,
                                               " m: the shank cannot reach it (asin(d / Ls) undefined)"));
  }
  if (!std::isfinite(force)) throw InvalidInput("Jig: crosshead force is not finite");
  JigSample s{};
  const double rotation = std::asin(d / ls);
  const double alpha = detail::radians(jig_.heel_bar_tilt_deg);
  const double theta = detail::radians(jig_.initial_angle_deg) + rotation;
  if (!(theta > 0.0 && theta < detail::kPi)) {
    throw InvalidInput(pamkit::detail::message(
        "Jig: a displacement of ", d, " m turns the shank ", detail::degrees(rotation),
        " deg, folding the shank onto the heel bar (initial_angle_deg = ", jig_.initial_angle_deg, ")"));
  }
  const double beta = 0.5 * detail::kPi + alpha - theta;  // G.4: beta = 95 deg - theta with alpha = 5 deg
  const double ax = ls * std::cos(beta) + linkage_.shank_offset_m * std::cos(beta + 0.5 * detail::kPi);
  const double ay = ls * std::sin(beta) + linkage_.shank_offset_m * std::sin(beta + 0.5 * detail::kPi);
  const double bx = linkage_.heel_offset_m * std::cos(alpha + 0.5 * detail::kPi);
  const double by = linkage_.heel_offset_m * std::sin(alpha + 0.5 * detail::kPi);
  const double length = std::hypot(bx - ax, by - ay);
  // Unit vector of the muscle's pull on the shank, from A towards B. G.4 takes its angle
  // gamma from acos, which drops the sign of the vertical part; with the signed vector the
  // two balances below use one direction.
  const double ux = (bx - ax) / length;
  const double uy = (by - ay) / length;
  // Shank section, moments about the ankle (figure 4.17): the crosshead's vertical force at
  // A's horizontal distance (G.4: A(i,3) * PointA(1,i)) balances the muscle's pull at A.
  const double arm_on_shank = ax * uy - ay * ux;
  const double muscle_force = force * ax / arm_on_shank;
  // Heel bar (figure 4.18): the muscle pulls B towards A; plantarflexion-positive moment.
  const double moment = -muscle_force * (bx * (-uy) - by * (-ux));
  s.rotation_deg = detail::degrees(rotation);
  s.heel_bar_angle_deg = detail::degrees(theta);
  s.muscle_length_m = length;
  s.muscle_force_N = muscle_force;
  s.ankle_moment_Nm = moment;
  return s;
}

/// A row of table 4.2: the mechanical tests of the prototype.
struct Table42Row {
  double gauge_pressure_Pa;        ///< PAM inflation, above the atmosphere [Pa]
  double muscle_length_m;          ///< measured between attachment points, end caps included [m]
  double angle_deg;                ///< theta at the start [deg]
  double vertical_displacement_m;  ///< crosshead travel [m]
};

/// Table 4.2 as printed (its pressures in kPa, here in Pa).
inline std::vector<Table42Row> table_4_2() {
  return {{70e3, 0.286, 80.0, 0.0503},
          {70e3, 0.286, 80.0, 0.0604},
          {55e3, 0.290, 82.0, 0.0703},
          {48e3, 0.295, 85.0, 0.0803}};
}

}  // namespace pamkit::exo
