#pragma once
/// \file
/// Spring laws for the exoskeleton: force [N] against the spring's elongation beyond its block
/// length [m]. Any callable `double(double elongation_m)` is a spring law for the device
/// (exo/device.hpp); these are the ones the thesis compared (section 4.3, figure 4.6).

#include <cmath>

#include "pamkit/fields.hpp"
#include "pamkit/gas/air.hpp"
#include "pamkit/muscle/force.hpp"

namespace pamkit::exo {

/// A linear (coil) spring, as in G.3: F = k e.
struct LinearSpring {
  static constexpr const char* kName = "LinearSpring";

  double stiffness_N_per_m = 6000.0;  ///< k [N/m] (G.3 `linearspringstiffness`)

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("stiffness_N_per_m", &LinearSpring::stiffness_N_per_m,
          FieldInfo{"N/m", 0.0, 1e8, "spring rate k (G.3 linearspringstiffness)"});
  }
  void validate() const { validate_fields(*this); }

  double operator()(double elongation_m) const { return stiffness_N_per_m * elongation_m; }
};

/// G.3's `pamequation`: a polynomial fitted by the thesis to one earlier PAM test,
/// F = 0.1687 (1000 e)^2 + 0.127 (1000 e) + 16.9 [N] with e in m (the text calls it fourth
/// order, the script's is second order; this is the script's).
struct ThesisPolynomialSpring {
  double operator()(double elongation_m) const {
    const double mm = 1000.0 * elongation_m;
    return 0.1687 * mm * mm + 0.127 * mm + 16.9;
  }
};

/// The muscle as a static spring: inflated to a gauge pressure at its free (zero-force)
/// length, sealed, mounted with a pre-stretch at the block, and stretched so slowly (or so
/// fast) that its gas follows a polytropic law p V^n = const (eq. 3.1.16). Force from
/// pamkit's virtual-work force (`muscle_forces`), friction left out: a static law has no rate.
class PamStaticSpring {
 public:
  /// \param free_length_m muscle length at which it was sealed (e.g. free_inflation's) [m]
  /// \param gauge_pressure_Pa sealed gauge pressure at that length [Pa]
  /// \param pretension_m muscle stretch beyond free_length_m when the heel bar is on the block [m]
  /// \param polytropic_index n of eq. 3.1.14 (1 isothermal: the thesis's best fit)
  /// \throws InvalidParameter for a bad build or gas, InvalidInput for a bad length or pressure.
  PamStaticSpring(const MuscleBuild& build, const BladderLaw& bladder, const GasParams& gas, double free_length_m,
                  double gauge_pressure_Pa, double pretension_m = 0.0, double polytropic_index = 1.0);

  /// Muscle force [N] at spring elongation `elongation_m` [m].
  /// \throws InvalidInput if the muscle would be longer than its braid allows.
  double operator()(double elongation_m) const;

  /// Muscle length at spring elongation `elongation_m` [m].
  double muscle_length(double elongation_m) const { return free_length_ + pretension_ + elongation_m; }
  /// Gauge pressure at spring elongation `elongation_m` [Pa].
  double gauge_pressure(double elongation_m) const;

 private:
  BraidGeometry geometry_;
  BladderLaw bladder_;
  GasParams gas_;
  double free_length_;
  double gauge_pressure_;
  double pretension_;
  double polytropic_index_;
  double initial_volume_;
};

inline PamStaticSpring::PamStaticSpring(const MuscleBuild& build, const BladderLaw& bladder, const GasParams& gas,
                                        double free_length_m, double gauge_pressure_Pa, double pretension_m,
                                        double polytropic_index)
    : geometry_((build.validate(), build)),
      bladder_(bladder),
      gas_((gas.validate(), gas)),
      free_length_(free_length_m),
      gauge_pressure_(gauge_pressure_Pa),
      pretension_(pretension_m),
      polytropic_index_(polytropic_index) {
  if (!(free_length_m > geometry_.min_length() && free_length_m < geometry_.max_length())) {
    throw InvalidInput(pamkit::detail::message("PamStaticSpring: free_length_m = ", free_length_m,
                                               " m is outside the braid's range (", geometry_.min_length(), ", ",
                                               geometry_.max_length(), ") m"));
  }
  if (!(gauge_pressure_Pa >= 0.0) || !std::isfinite(gauge_pressure_Pa)) {
    throw InvalidInput(
        pamkit::detail::message("PamStaticSpring: gauge_pressure_Pa = ", gauge_pressure_Pa, " must be >= 0"));
  }
  if (!(pretension_m >= 0.0) || !std::isfinite(pretension_m)) {
    throw InvalidInput(pamkit::detail::message("PamStaticSpring: pretension_m = ", pretension_m, " must be >= 0"));
  }
  if (!(polytropic_index >= 1.0 && polytropic_index <= 1.7)) {
    throw InvalidInput(
        pamkit::detail::message("PamStaticSpring: polytropic_index = ", polytropic_index, " is outside [1, 1.7]"));
  }
  initial_volume_ = geometry_.shape(free_length_m).gas_volume;
}

inline double PamStaticSpring::gauge_pressure(double elongation_m) const {
  const double length = muscle_length(elongation_m);
  if (!(length < geometry_.max_length())) {
    throw InvalidInput(pamkit::detail::message("PamStaticSpring: elongation ", elongation_m,
                                               " m stretches the muscle to ", length, " m, beyond the braid's longest ",
                                               geometry_.max_length(), " m"));
  }
  const double p0 = gas_.atmospheric_pressure_Pa + gauge_pressure_;
  return polytropic_pressure(p0, initial_volume_, geometry_.shape(length).gas_volume, polytropic_index_) -
         gas_.atmospheric_pressure_Pa;
}

inline double PamStaticSpring::operator()(double elongation_m) const {
  const double gauge = gauge_pressure(elongation_m);
  const FrictionParams no_friction{0.0, 0.0, 0.0, 0.0, 0.0};
  const MuscleShape shape = geometry_.shape(muscle_length(elongation_m));
  return muscle_forces(geometry_, shape, bladder_, no_friction, gas_.atmospheric_pressure_Pa + gauge,
                       gas_.atmospheric_pressure_Pa, 0.0)
      .total;
}

}  // namespace pamkit::exo
