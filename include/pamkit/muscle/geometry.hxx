#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <boost/math/tools/roots.hpp>

namespace pamkit {

namespace detail {
constexpr double kPi = 3.14159265358979323846;

/// Axial length of a cone of slant `generator` joining diameters D and d.
inline double cone_axial_length(double generator, double diameter, double end_diameter) {
  const double c = 0.5 * (diameter - end_diameter);
  return std::sqrt(std::max(generator * generator - c * c, 0.0));
}
}  // namespace detail

inline double braid_diameter(double fiber_length_m, double revolutions, double braid_angle_rad) {
  return fiber_length_m * std::sin(braid_angle_rad) / (detail::kPi * revolutions);
}

inline double braid_cylinder_length(double fiber_length_m, double braid_angle_rad) {
  return fiber_length_m * std::cos(braid_angle_rad);
}

inline double braid_fiber_length(double cylinder_length_m, double diameter_m, double revolutions) {
  return std::hypot(cylinder_length_m, detail::kPi * revolutions * diameter_m);
}

namespace detail {
/// Axial length of one end [m]: a cone's, or a flat flange's end zone (0 without one).
inline double deflated_end_length(const MuscleBuild& build) {
  const bool has_cones = build.cone_generator_m > 0.0;
  return has_cones ? cone_axial_length(build.cone_generator_m, build.diameter_m, build.end_diameter_m)
                   : build.end_zone_m;
}
inline double deflated_cylinder_length(const MuscleBuild& build) {
  return build.length_m - 2.0 * deflated_end_length(build);
}
}  // namespace detail

inline double deflated_braid_angle_deg(const MuscleBuild& build) {
  const double tangent =
      detail::kPi * build.fiber_revolutions * build.diameter_m / detail::deflated_cylinder_length(build);
  return std::atan(tangent) * 180.0 / detail::kPi;
}

inline double fiber_revolutions_for_braid_angle(const MuscleBuild& build, double braid_angle_deg) {
  if (!(braid_angle_deg > 0.0 && braid_angle_deg < 90.0)) {
    PAMKIT_THROW(InvalidParameter(
        detail::message("braid_angle_deg = ", braid_angle_deg, " must lie strictly between 0 and 90 degrees")));
  }
  return detail::deflated_cylinder_length(build) * std::tan(braid_angle_deg * detail::kPi / 180.0) /
         (detail::kPi * build.diameter_m);
}

inline BraidGeometry::BraidGeometry(const MuscleBuild& build) : build_(build) {
  build_.validate();
  deflated_cylinder_length_ = detail::deflated_cylinder_length(build_);
  const double tb = build_.bladder_thickness_m;
  wall_volume_ = detail::kPi * build_.length_m * (build_.diameter_m * tb - tb * tb);
  fiber_length_ = braid_fiber_length(deflated_cylinder_length_, build_.diameter_m, build_.fiber_revolutions);
  min_length_ = min_length_for_fibers(fiber_length_);
  max_length_ = max_length_for_fibers(fiber_length_);
}

inline double BraidGeometry::min_length_for_fibers(double fiber_length_m) const noexcept {
  const double lz = build_.cone_generator_m;
  // Flat ends: the end zones keep their length, the cylinder between them spans 0 to Lym.
  if (!(lz > 0.0)) return 2.0 * build_.end_zone_m;
  // Shortest: the cones lie flat (D = d + 2 Lz, LL = 0), unless the braid reaches 90 degrees first.
  const double turns = detail::kPi * build_.fiber_revolutions;
  const double widest = build_.end_diameter_m + 2.0 * lz;
  if (turns * widest >= fiber_length_m) return 0.0;
  return std::sqrt(fiber_length_m * fiber_length_m - turns * turns * widest * widest);
}

inline double BraidGeometry::max_length_for_fibers(double fiber_length_m) const noexcept {
  const double lz = build_.cone_generator_m;
  if (!(lz > 0.0)) return fiber_length_m + 2.0 * build_.end_zone_m;
  // Longest: the braid narrows to the end caps' diameter d.
  const double turns = detail::kPi * build_.fiber_revolutions;
  const double d = build_.end_diameter_m;
  return 2.0 * lz + std::sqrt(fiber_length_m * fiber_length_m - turns * turns * d * d);
}

inline double BraidGeometry::longest_fiber_length(double length_m) const noexcept {
  const double lz = build_.cone_generator_m;
  if (!(lz > 0.0)) return std::numeric_limits<double>::infinity();
  const double turns = detail::kPi * build_.fiber_revolutions;
  return std::hypot(length_m, turns * (build_.end_diameter_m + 2.0 * lz));
}

inline void BraidGeometry::check_range(double length_m) const {
  if (!(length_m > min_length_ && length_m < max_length_)) {
    PAMKIT_THROW(
        InvalidInput(detail::message("muscle length ", length_m, " m is outside the range the braid model allows (",
                                     min_length_, ", ", max_length_, ") m for this build")));
  }
}

inline MuscleShape BraidGeometry::shape(double length_m) const {
  check_range(length_m);
  return shape_unchecked(length_m);
}

inline MuscleShape BraidGeometry::shape_from(ShapeHint& hint, double length_m, ShapeParts parts) const {
  check_range(length_m);
  return solve(hint, length_m, fiber_length_, parts);
}

inline MuscleShape BraidGeometry::shape_from(ShapeHint& hint, double length_m, double fiber_length_m,
                                             ShapeParts parts) const {
  const double shortest = min_length_for_fibers(fiber_length_m);
  const double longest = max_length_for_fibers(fiber_length_m);
  if (!(length_m > shortest && length_m < longest)) {
    PAMKIT_THROW(
        InvalidInput(detail::message("muscle length ", length_m, " m is outside the range the braid model allows (",
                                     shortest, ", ", longest, ") m for fibers of length ", fiber_length_m, " m")));
  }
  return solve(hint, length_m, fiber_length_m, parts);
}

inline FiberLengthDerivatives BraidGeometry::fiber_length_derivatives(const MuscleShape& shape,
                                                                      double fiber_length_m) const noexcept {
  // At fixed L every quantity X is X(D, L), D solving the closure
  //     G(D; L, b) = (pi n D)^2 + (L - 2 LL(D))^2 - b^2 = 0,
  // so dX/db = X_D D_b and the second derivatives follow by the chain rule. With
  // g = G_D / 2 = (pi n)^2 D + Lm c / LL (the denominator of dD/dL = -Lm / g):
  //     D_b = b / g,  D_bb = (1 - b g_D D_b / g) / g,  D_bL = -b (g_L + g_D D_L) / g^2.
  // The cone LL = sqrt(Lz^2 - c^2), c = (D - d) / 2: LL' = -c / (2 LL), LL'' = -Lz^2 / (4 LL^3);
  // flat ends keep LL fixed.
  const double pi = detail::kPi;
  const double n = build_.fiber_revolutions;
  const double k2 = pi * pi * n * n;
  const double d = build_.end_diameter_m;
  const double lz = build_.cone_generator_m;
  const double b = fiber_length_m;
  const double D = shape.diameter;
  const double ll = shape.cone_length;
  const double lm = shape.cylinder_length;
  const double c = 0.5 * (D - d);
  const bool has_cones = lz > 0.0;
  const double ll_d = has_cones ? -c / (2.0 * ll) : 0.0;
  const double ll_dd = has_cones ? -lz * lz / (4.0 * ll * ll * ll) : 0.0;
  const double g = k2 * D + (has_cones ? lm * c / ll : 0.0);
  // d(Lm c / LL)/dD with Lm_D = -2 LL', c' = 1/2; d(Lm c / LL)/dL = c / LL.
  const double g_d = k2 + (has_cones ? (-2.0 * ll_d * c + 0.5 * lm) / ll - lm * c * ll_d / (ll * ll) : 0.0);
  const double g_l = has_cones ? c / ll : 0.0;
  const double d_l = shape.d_diameter;  // dD/dL at fixed b: -Lm / g

  FiberLengthDerivatives f{};
  f.d_diameter = b / g;
  f.d2_diameter = (1.0 - b * g_d * f.d_diameter / g) / g;
  f.d_diameter_d_length = -b * (g_l + g_d * d_l) / (g * g);
  // Lm = L - 2 LL(D).
  f.d_cylinder_length = -2.0 * ll_d * f.d_diameter;
  f.d2_cylinder_length = -2.0 * (ll_dd * f.d_diameter * f.d_diameter + ll_d * f.d2_diameter);
  f.d_cylinder_length_d_length = -2.0 * (ll_dd * d_l * f.d_diameter + ll_d * f.d_diameter_d_length);
  // V_total(D, L): the cylinder pi D^2 Lm / 4 and, with cones, the two frusta of eq. 3.1.1,
  // 2/3 pi LL F(D), F = (D^2 + d^2 + d D) / 4. V_D, V_DD at fixed L; V_DL = pi D / 2.
  double v_d = 0.25 * pi * (2.0 * D * lm - 2.0 * D * D * ll_d);
  double v_dd = 0.25 * pi * (2.0 * lm - 8.0 * D * ll_d - 2.0 * D * D * ll_dd);
  if (has_cones) {
    const double frustum = 0.25 * (D * D + d * d + d * D);
    const double frustum_d = 0.25 * (2.0 * D + d);
    v_d += (2.0 / 3.0) * pi * (ll_d * frustum + ll * frustum_d);
    v_dd += (2.0 / 3.0) * pi * (ll_dd * frustum + 2.0 * ll_d * frustum_d + 0.5 * ll);
  }
  const double v_dl = 0.5 * pi * D;
  f.d_gas_volume = v_d * f.d_diameter;
  f.d2_gas_volume = v_dd * f.d_diameter * f.d_diameter + v_d * f.d2_diameter;
  f.d_gas_volume_d_length = (v_dl + v_dd * d_l) * f.d_diameter + v_d * f.d_diameter_d_length;
  return f;
}

inline MuscleShape BraidGeometry::shape_unchecked(double length_m) const noexcept {
  ShapeHint cold;
  return solve(cold, length_m, fiber_length_, ShapeParts::all);
}

inline MuscleShape BraidGeometry::solve(ShapeHint& hint, double length_m, double fiber_length_m,
                                        ShapeParts parts) const noexcept {
  // Inside the range the closure below brackets its root (G(d) < 0 < G(d + 2 Lz)), so Boost's
  // Newton iteration has no cause to raise its "no root" error.
  const double n = build_.fiber_revolutions;
  const double k2 = detail::kPi * detail::kPi * n * n;  // (pi n)^2
  const double d = build_.end_diameter_m;
  const double lz = build_.cone_generator_m;
  const double lym = fiber_length_m;

  MuscleShape s{};
  s.length = length_m;
  if (lz > 0.0) {
    // Closure of braid (eq. 3.1.11) and cones: G(D) = (pi n D)^2 + (L - 2 LL(D))^2 - Lym^2 = 0.
    // G rises monotonically in D on (d, d + 2 Lz), so a bracketed Newton iteration converges
    // from any guess inside; a good one only saves iterations.
    auto closure = [&](double diameter) {
      const double ll = detail::cone_axial_length(lz, diameter, d);
      const double lm = length_m - 2.0 * ll;
      const double c = 0.5 * (diameter - d);
      const double g = k2 * diameter * diameter + lm * lm - lym * lym;
      const double dg = 2.0 * k2 * diameter + (ll > 0.0 ? 2.0 * lm * c / ll : 1e30);
      return std::make_pair(g, dg);
    };
    const double lower = d;
    const double upper = d + 2.0 * lz;
    // From a hint, its diameter extrapolated to this length; without one, the diameter of a
    // cylinder of this length (as if the cones were flat).
    const double guess = hint.length_m > 0.0 ? hint.diameter_m + hint.d_diameter * (length_m - hint.length_m)
                                             : std::sqrt(std::max(lym * lym - length_m * length_m, 0.0) / k2);
    std::uintmax_t iterations = 100;
    s.diameter =
        boost::math::tools::newton_raphson_iterate(closure, std::clamp(guess, lower + 1e-12, upper - 1e-12), lower,
                                                   upper, std::numeric_limits<double>::digits - 6, iterations);
    s.cone_length = detail::cone_axial_length(lz, s.diameter, d);
  } else {
    const double cylinder = length_m - 2.0 * build_.end_zone_m;
    s.diameter = std::sqrt((lym * lym - cylinder * cylinder) / k2);
    s.cone_length = build_.end_zone_m;
  }
  const double D = s.diameter;
  const double ll = s.cone_length;
  const double lm = length_m - 2.0 * ll;
  const double c = 0.5 * (D - d);
  s.cylinder_length = lm;
  constexpr double left_out = std::numeric_limits<double>::quiet_NaN();
  s.braid_angle = parts == ShapeParts::kinematics ? left_out : std::atan2(detail::kPi * n * D, lm);
  if (parts != ShapeParts::all) {
    s.end_braid_angle = s.cone_angle = s.mean_braid_angle = left_out;
  } else if (lz > 0.0) {
    s.end_braid_angle = std::asin(std::min(1.0, d / D * std::sin(s.braid_angle)));
    s.cone_angle = std::asin(std::min(1.0, c / lz));
  } else {
    s.end_braid_angle = s.braid_angle;
    s.cone_angle = 0.0;
  }
  if (parts == ShapeParts::all) s.mean_braid_angle = 0.5 * (s.braid_angle + s.end_braid_angle);

  // Derivatives from the implicit closure: dD/dL = -G_L / G_D.
  const double cone_term = (lz > 0.0) ? lm * c / ll : 0.0;
  s.d_diameter = -lm / (k2 * D + cone_term);
  const double d_cone_length = (lz > 0.0) ? -c * s.d_diameter / (2.0 * ll) : 0.0;
  s.d_cylinder_length = 1.0 - 2.0 * d_cone_length;
  hint = ShapeHint{length_m, D, s.d_diameter};

  const double pi = detail::kPi;
  const double cylinder_volume = 0.25 * pi * D * D * lm;
  const double d_cylinder_volume = 0.25 * pi * (2.0 * D * s.d_diameter * lm + D * D * s.d_cylinder_length);
  if (lz > 0.0) {
    // Eq. 3.1.1: two frusta and a cylinder.
    const double frustum = 0.25 * (D * D + d * d + d * D);
    const double d_frustum = 0.25 * (2.0 * D + d) * s.d_diameter;
    s.total_volume = (2.0 / 3.0) * pi * ll * frustum + cylinder_volume;
    s.d_total_volume = (2.0 / 3.0) * pi * (d_cone_length * frustum + ll * d_frustum) + d_cylinder_volume;
  } else {
    // Flat ends: each end zone keeps its deflated diameter and length, so its volume.
    const double d0 = build_.diameter_m;
    s.total_volume = 0.5 * pi * d0 * d0 * build_.end_zone_m + cylinder_volume;
    s.d_total_volume = d_cylinder_volume;
  }
  // The wall conserves its volume: rubber is incompressible. Eq. 3.1.3 (a tube of the full
  // length, the braid's diameter and a fixed thickness) gives that volume on the deflated build;
  // evaluated at every length, as the thesis does, it would let the rubber's volume follow the
  // length and the absolute pressure do work on it (a force at zero gauge pressure).
  s.bladder_volume = wall_volume_;
  s.d_bladder_volume = 0.0;
  s.gas_volume = s.total_volume - s.bladder_volume;
  s.d_gas_volume = s.d_total_volume - s.d_bladder_volume;
  return s;
}

}  // namespace pamkit
