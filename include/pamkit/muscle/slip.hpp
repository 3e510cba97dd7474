#pragma once
/// \file
/// Friction with memory: a Maxwell-slip model of the rubber and the fibres rubbing inside the
/// membrane as the braid moves (Lampaert, Al-Bender and Swevers 2003; applied to pneumatic muscles
/// by Vo-Minh et al. 2011). Rate-independent: a loop survives settled steps, and what the elements
/// hold when the motion stops stays there, so a muscle that contracted to a held length carries
/// less than its elastic force, and one that lengthened to it carries more, at any pressure
/// (a vented muscle included).
///
/// `kSlipElements` elastic-perfectly-plastic elements in parallel, element i (1..N) with slip
/// force f / N and break-away displacement delta (i - 1/2) / N, stiffness f / (N delta_i): the
/// Prandtl-Ishlinskii operator with a uniform density of break-away displacements in (0, delta],
/// by the midpoint rule in N steps. From rest, a motion x loads the elements along the virgin curve
/// f (2 x / delta - (x / delta)^2) (N -> infinity), which reaches f at x = delta; after a
/// reversal the curve is the virgin one doubled (Masing's rule), so a loop's width is set by two
/// numbers: the slip force f and the break-away displacement delta.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace pamkit {

/// Number of Maxwell-slip elements (the Prandtl-Ishlinskii density in that many steps).
constexpr std::size_t kSlipElements = 16;

/// What the Maxwell-slip elements hold: each element's force [N], > 0 in tension (it adds to the
/// muscle's pull: the braid lengthened against it). All zero: the muscle at rest, never moved.
/// Mutable: it belongs to one run or one controller's loop, never to shared parameters.
struct SlipState {
  std::array<double, kSlipElements> force_N{};  ///< element forces [N]

  /// The elements' sum [N]: what they add to the muscle's tension.
  double total_N() const noexcept {
    double sum = 0.0;
    for (double f : force_N) sum += f;
    return sum;
  }
};

/// Slip force [N] of each element of a model whose elements slip at `slip_force_N` together.
inline double slip_element_force(double slip_force_N) noexcept {
  return slip_force_N / static_cast<double>(kSlipElements);
}

/// Stiffness [N/m] of element `index` (0-based): its slip force over its break-away displacement
/// slip_distance_m (index + 1/2) / N.
inline double slip_element_stiffness(double slip_force_N, double slip_distance_m, std::size_t index) noexcept {
  return slip_element_force(slip_force_N) * static_cast<double>(kSlipElements) /
         (slip_distance_m * (static_cast<double>(index) + 0.5));
}

/// Moves the elements by a braid displacement `displacement_m` [m] in one direction (> 0:
/// lengthening), exactly: each element's force follows its stiffness and stops at its slip force.
/// \returns the energy the slipping dissipated [J] (>= 0): what the elements took in and do not
/// hold as spring energy.
inline double slip_move(SlipState& state, double slip_force_N, double slip_distance_m, double displacement_m) noexcept {
  if (slip_force_N <= 0.0) return 0.0;
  const double limit = slip_element_force(slip_force_N);
  double dissipated = 0.0;
  for (std::size_t i = 0; i < kSlipElements; ++i) {
    const double k = slip_element_stiffness(slip_force_N, slip_distance_m, i);
    const double free = state.force_N[i] + k * displacement_m;
    const double held = std::clamp(free, -limit, limit);
    // The part of the motion beyond where the element reached its limit slips at that limit.
    dissipated += limit * std::abs(free - held) / k;
    state.force_N[i] = held;
  }
  return dissipated;
}

/// The elements' sum [N] after a displacement `displacement_m` from `state`, which is left as it
/// is: a trial move, for a search along a motion.
inline double slip_total_after(const SlipState& state, double slip_force_N, double slip_distance_m,
                               double displacement_m) noexcept {
  if (slip_force_N <= 0.0) return 0.0;
  const double limit = slip_element_force(slip_force_N);
  double sum = 0.0;
  for (std::size_t i = 0; i < kSlipElements; ++i) {
    const double k = slip_element_stiffness(slip_force_N, slip_distance_m, i);
    sum += std::clamp(state.force_N[i] + k * displacement_m, -limit, limit);
  }
  return sum;
}

/// Spring energy the elements hold [J]: sum of force^2 / (2 stiffness).
inline double slip_stored_energy(const SlipState& state, double slip_force_N, double slip_distance_m) noexcept {
  if (slip_force_N <= 0.0) return 0.0;
  double energy = 0.0;
  for (std::size_t i = 0; i < kSlipElements; ++i) {
    energy += state.force_N[i] * state.force_N[i] / (2.0 * slip_element_stiffness(slip_force_N, slip_distance_m, i));
  }
  return energy;
}

}  // namespace pamkit
