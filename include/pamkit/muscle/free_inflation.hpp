#pragma once
/// \file
/// Free inflation: the length and diameter a muscle takes when inflated with no load.

#include <cmath>
#include <cstdint>

#include <boost/math/tools/roots.hpp>

#include "pamkit/muscle/force.hpp"

namespace pamkit {

/// Result of inflating a muscle with no load at its ends.
struct FreeInflation {
  double length_m;    ///< free (zero-force) length [m]
  double diameter_m;  ///< braid diameter at that length [m]
  bool contracted;    ///< false if the bladder resists more than the pressure can push, so
                      ///< the muscle stays at its deflated length
};

/// Inflates the deflated build to `gauge_pressure_Pa` with no load and returns where the
/// elastic force (gas plus bladder, no friction) first falls to zero as the muscle contracts
/// from its deflated length. The pressure is held (the muscle hangs on the supply while it
/// is inflated, section 3.2.1).
/// \throws InvalidInput if the pressure is negative or the force never reaches zero.
inline FreeInflation free_inflation(const BraidGeometry& geometry, const BladderLaw& law,
                                    double atmospheric_pressure_Pa, double gauge_pressure_Pa) {
  if (!(gauge_pressure_Pa >= 0.0) || !std::isfinite(gauge_pressure_Pa)) {
    PAMKIT_THROW(
        InvalidInput(detail::message("free_inflation: gauge pressure ", gauge_pressure_Pa, " Pa must be >= 0")));
  }
  const FrictionParams no_friction{0.0, 0.0, 0.0, 0.0, 0.0};
  auto force = [&](double length) {
    return muscle_forces(geometry, geometry.shape(length), law, no_friction,
                         atmospheric_pressure_Pa + gauge_pressure_Pa, atmospheric_pressure_Pa, 0.0)
        .total;
  };
  const double deflated = geometry.build().length_m;
  if (force(deflated) <= 0.0) {
    return {deflated, geometry.build().diameter_m, false};
  }
  // Walk down from the deflated length to the first sign change, then refine it.
  const double shortest = geometry.min_length() * (1.0 + 1e-9) + 1e-12;
  constexpr int kScanSteps = 400;
  double upper = deflated;
  for (int i = 1; i <= kScanSteps; ++i) {
    const double lower = deflated - (deflated - shortest) * i / kScanSteps;
    if (force(lower) <= 0.0) {
      std::uintmax_t iterations = 200;
      const auto bracket = boost::math::tools::toms748_solve(force, lower, upper,
                                                             boost::math::tools::eps_tolerance<double>(50), iterations);
      const double length = 0.5 * (bracket.first + bracket.second);
      return {length, geometry.shape(length).diameter, true};
    }
    upper = lower;
  }
  PAMKIT_THROW(InvalidInput(detail::message(
      "free_inflation: at ", gauge_pressure_Pa,
      " Pa gauge the force stays positive down to the shortest length the braid model allows (", shortest, " m)")));
}

}  // namespace pamkit
