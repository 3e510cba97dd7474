#pragma once
/// \file
/// Friction with memory: a Maxwell-slip model of the rubber and the fibres rubbing inside the
/// membrane as the braid moves (Lampaert, Al-Bender and Swevers 2003; applied to pneumatic muscles
/// by Vo-Minh et al. 2011). Rate-independent: a loop survives settled steps, and what the elements
/// hold when the motion stops stays there, so a muscle that contracted to a held length carries
/// less than its elastic force, and one that lengthened to it carries more, at any pressure
/// (a vented muscle included).
///
/// `kSlipElements` elastic-perfectly-plastic elements in parallel (Iwan's distributed-element
/// model, Iwan 1966): every element springs with the same stiffness 2 f / (N delta), the stiffness
/// of the fibres' bond to the rubber, and element i (0..N-1) breaks away at displacement
/// delta (i + 1/2) / N, so it slips at f (2 i + 1) / N^2: break-away displacements spread evenly
/// over (0, delta], the elements' slip forces summing to f. From rest, a motion x loads them along
/// the virgin curve f (2 x / delta - (x / delta)^2), which reaches f at x = delta with zero slope
/// (the N elements' curve is made of its tangents at m delta / N, within f / (4 N^2) of it); after
/// a reversal the curve is the virgin one doubled (Masing's rule), so a loop's width is set by two
/// numbers: the slip force f and the break-away displacement delta. Near rest the elements are as
/// stiff as the bond, 2 f / delta: a small motion takes up friction in proportion to it. (Equal
/// slip forces at the same break-aways would make the elements' stiffnesses sum to a logarithm
/// that grows without bound with N: a muscle infinitely stiff against its first motion.)

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace pamkit {

/// Number of Maxwell-slip elements (the even spread of break-away displacements in that many steps).
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

/// Slip force [N] of element `index` (0-based) of a model whose elements slip at `slip_force_N`
/// together: f (2 index + 1) / N^2.
inline double slip_element_force(double slip_force_N, std::size_t index) noexcept {
  const double n = static_cast<double>(kSlipElements);
  return slip_force_N * (2.0 * static_cast<double>(index) + 1.0) / (n * n);
}

/// Stiffness [N/m] of every element: 2 f / (N delta), so that element `index` breaks away at
/// delta (index + 1/2) / N.
inline double slip_element_stiffness(double slip_force_N, double slip_distance_m) noexcept {
  return 2.0 * slip_force_N / (static_cast<double>(kSlipElements) * slip_distance_m);
}

/// The virgin curve [N] the elements approximate, from rest: f (2 u - u^2) for u = |x| / delta
/// below 1, f beyond, with the sign of the displacement `displacement_m` [m].
inline double slip_virgin_force(double slip_force_N, double slip_distance_m, double displacement_m) noexcept {
  const double u = std::min(std::abs(displacement_m) / slip_distance_m, 1.0);
  const double force = slip_force_N * u * (2.0 - u);
  return displacement_m < 0.0 ? -force : force;
}

/// Moves the elements by a braid displacement `displacement_m` [m] in one direction (> 0:
/// lengthening), exactly: each element's force follows its stiffness and stops at its slip force.
/// \returns the energy the slipping dissipated [J] (>= 0): what the elements took in and do not
/// hold as spring energy.
inline double slip_move(SlipState& state, double slip_force_N, double slip_distance_m, double displacement_m) noexcept {
  if (slip_force_N <= 0.0) return 0.0;
  const double k = slip_element_stiffness(slip_force_N, slip_distance_m);
  double dissipated = 0.0;
  for (std::size_t i = 0; i < kSlipElements; ++i) {
    const double limit = slip_element_force(slip_force_N, i);
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
  const double k = slip_element_stiffness(slip_force_N, slip_distance_m);
  double sum = 0.0;
  for (std::size_t i = 0; i < kSlipElements; ++i) {
    const double limit = slip_element_force(slip_force_N, i);
    sum += std::clamp(state.force_N[i] + k * displacement_m, -limit, limit);
  }
  return sum;
}

/// Spring energy the elements hold [J]: the sum of force^2 / (2 stiffness).
inline double slip_stored_energy(const SlipState& state, double slip_force_N, double slip_distance_m) noexcept {
  if (slip_force_N <= 0.0) return 0.0;
  double squares = 0.0;
  for (double force : state.force_N) squares += force * force;
  return squares / (2.0 * slip_element_stiffness(slip_force_N, slip_distance_m));
}

}  // namespace pamkit
