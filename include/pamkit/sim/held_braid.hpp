#pragma once
/// \file
/// A muscle whose ends a rig holds at a length while the supplied pressure moves, settled at each
/// step: an isometric map's held length, a supplied test's crosshead, a controller's linkage.
/// Where the braid can go slack and the Maxwell-slip elements (muscle/slip.hpp) remember its
/// motion, where the braid is matters, not only where the ends are: pulled taut it lies at the
/// held length; slack (it would push there) it is free and settles where it carries nothing,
/// shorter or longer than its last place as the pressure drives it, and the elements follow that
/// motion. An isometric map's muscle, held shorter than its rest length, contracts that way while
/// the pressure rises until it pulls taut, and keeps what the elements took up on the way.

#include <algorithm>
#include <cstdint>

#include <boost/math/tools/roots.hpp>

#include "pamkit/sim/model.hpp"

namespace pamkit {

/// Where a held muscle's braid is and what its slip elements hold. Mutable: one per run, or one
/// per controller (RealtimeMuscle's workspace).
struct HeldBraidState {
  double braid_length_m = 0.0;  ///< the braid's length [m]: the held length when taut, longer or shorter when slack
  SlipState slip;               ///< what the Maxwell-slip elements hold
};

/// Where a braid pulled (or pushed) by the parts in series with it lies: the length b between
/// `held_length_m` and `held_length_m - c F(held)` at which the force `carried(b)` (rising in b)
/// stretches them by `held_length_m - b` (MuscleBuild::series_compliance_m_per_N = c), within
/// the braid's range.
template <class Carried>
double yielded_braid_length(const BraidGeometry& geometry, Carried&& carried, double held_length_m, double force_held_N,
                            double compliance_m_per_N) noexcept {
  const auto imbalance = [&](double braid) { return carried(braid) - (held_length_m - braid) / compliance_m_per_N; };
  const double yielded = held_length_m - compliance_m_per_N * force_held_N;
  const double lower = std::max(std::min(held_length_m, yielded), geometry.min_length() * (1.0 + 1e-9));
  const double upper = std::min(std::max(held_length_m, yielded), geometry.max_length() * (1.0 - 1e-9));
  const double at_lower = imbalance(lower);
  const double at_upper = imbalance(upper);
  if (!(at_lower < 0.0)) return lower;  // the range ends first
  if (!(at_upper > 0.0)) return upper;
  std::uintmax_t iterations = 100;
  const auto root = boost::math::tools::toms748_solve(imbalance, lower, upper, at_lower, at_upper,
                                                      boost::math::tools::eps_tolerance<double>(40), iterations);
  return 0.5 * (root.first + root.second);
}

/// Where a held braid lies when its force at the held length, `force_held_N`, is `carried(held)`:
/// at the held length, or with a series compliance short of it (yielded_braid_length), unless it
/// is an embedded braid that would push there (slack: nothing stretches the parts in series).
template <class Carried>
double pulled_braid_length(const BraidGeometry& geometry, const MuscleParams& extended, Carried&& carried,
                           double held_length_m, double force_held_N) noexcept {
  const double compliance = extended.build.series_compliance_m_per_N;
  const bool yields = compliance > 0.0 && (force_held_N > 0.0 || detail::slack_band_N(extended) <= 0.0);
  return yields ? yielded_braid_length(geometry, carried, held_length_m, force_held_N, compliance) : held_length_m;
}

/// The held braid at rest: at the deflated length, nothing in the slip elements.
inline HeldBraidState braid_at_rest(const MuscleBuild& build) noexcept { return {build.length_m, {}}; }

/// The force [N] a load cell reads of a muscle whose ends are held at `length_m` (inside the
/// braid's range, which the caller checked) at supplied gauge pressure `gauge_Pa`, elongation
/// rate `velocity_m_per_s` (the tanh friction's) and pressure `branch` (+1 pressurising, -1
/// venting, 0 neither: detail::supplied_force), the braid settled from `state`, which it updates.
///
/// Without slip elements or a series compliance the braid's place carries no memory, and this is
/// `detail::supplied_force` at the held length, operation for operation. Taut (the force at the
/// held length, the elements moved there, is not below zero, or the braid can push) the braid
/// lies at the held length, or with a series compliance short of it by what its pull stretches
/// the parts in series (`yielded_braid_length`); slack, it moves from where it was to where its
/// force, elements included, is zero, between the held length and the braid's longest length,
/// and the load cell reads the slack force (through `braid_tension`, at most a quarter of its
/// band).
inline double settle_held_braid(const BraidGeometry& geometry, const MuscleParams& extended, HeldBraidState& state,
                                double length_m, double gauge_Pa, double velocity_m_per_s, double branch) noexcept {
  const ModelExtensions& x = extended.extensions;
  const double band = detail::slack_band_N(extended);
  const double from = state.braid_length_m;
  const auto carried = [&](double braid) {
    return detail::unslackened_supplied_force(
        geometry, extended, geometry.shape_unchecked(braid), gauge_Pa, velocity_m_per_s, branch,
        slip_total_after(state.slip, x.slip_force_N, x.slip_distance_m, braid - from));
  };
  const double taut = carried(length_m);
  if (x.slip_force_N <= 0.0 || band <= 0.0 || taut >= 0.0) {
    const double braid = pulled_braid_length(geometry, extended, carried, length_m, taut);
    const double force = braid == length_m ? taut : carried(braid);  // before the elements move there
    slip_move(state.slip, x.slip_force_N, x.slip_distance_m, braid - from);
    state.braid_length_m = braid;
    return braid_tension(force, band);
  }
  // Slack: the free braid carries nothing. Its force rises with its length (the gas's and the
  // membrane's, and the elements'), and is below zero at the held length.
  double lower = length_m;
  double upper = from;
  if (!(from > length_m && carried(from) >= 0.0)) {
    lower = std::max(length_m, from);
    const double top = geometry.max_length() * (1.0 - 1e-9);
    const double step = 0.0025 * (top - geometry.min_length());
    upper = lower;
    while (upper < top && carried(upper) < 0.0) {
      lower = upper;
      upper = std::min(upper + step, top);
    }
  }
  double braid = upper;
  if (upper > lower && carried(upper) >= 0.0) {
    std::uintmax_t iterations = 100;
    const auto root = boost::math::tools::toms748_solve(carried, lower, upper,
                                                        boost::math::tools::eps_tolerance<double>(40), iterations);
    braid = 0.5 * (root.first + root.second);
  }
  slip_move(state.slip, x.slip_force_N, x.slip_distance_m, braid - from);
  state.braid_length_m = braid;
  return braid_tension(taut, band);
}

}  // namespace pamkit
