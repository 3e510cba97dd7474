"""Cycles of a stretch protocol, and the split into cycles to fit and cycles to hold out."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Cycles:
    """Sample index ranges of the stretch cycles: cycle k is samples [starts[k], ends[k])."""

    starts: np.ndarray
    ends: np.ndarray

    def __len__(self) -> int:
        return len(self.starts)

    def index(self, n_samples: int) -> np.ndarray:
        """Cycle number of every sample (-1 before the first cycle)."""
        label = np.full(n_samples, -1)
        for k, (start, end) in enumerate(zip(self.starts, self.ends)):
            label[start:end] = k
        return label

    def half_cycle_index(self, elongation: np.ndarray) -> np.ndarray:
        """Half-cycle number of every sample: 2k while cycle k stretches, 2k+1 while it returns."""
        label = np.full(len(elongation), -1)
        for k, (start, end) in enumerate(zip(self.starts, self.ends)):
            top = start + int(np.argmax(elongation[start:end]))
            label[start:top] = 2 * k
            label[top:end] = 2 * k + 1
        return label


def find_cycles(elongation: np.ndarray, min_relative_travel: float = 0.5) -> Cycles:
    """Finds stretch cycles from the crosshead's elongation: a cycle runs from one low turning
    point to the next and reaches at least `min_relative_travel` of the largest elongation.
    Noise in the elongation is tolerated: turning points must be separated by that travel."""
    e = np.asarray(elongation, dtype=float)
    span = float(e.max() - e.min())
    if span <= 0:
        return Cycles(np.array([], dtype=int), np.array([], dtype=int))
    threshold = min_relative_travel * span
    # Hysteresis turning-point detection: a low is confirmed once the signal rises by the
    # threshold above it, a high once it falls by the threshold below it.
    lows = [0]
    looking_for_high = True
    extreme_index = 0
    for i in range(1, len(e)):
        if looking_for_high:
            if e[i] < e[extreme_index]:
                extreme_index = i
                lows[-1] = i
            elif e[i] - e[extreme_index] > threshold:
                looking_for_high = False
                extreme_index = i
        else:
            if e[i] > e[extreme_index]:
                extreme_index = i
            elif e[extreme_index] - e[i] > threshold:
                looking_for_high = True
                extreme_index = i
                lows.append(i)
    # The last low confirmed is where the latest cycle ended; extend it to its true minimum.
    if looking_for_high and len(lows) > 1:
        tail = lows[-1]
        lows[-1] = tail + int(np.argmin(e[tail:]))
    return Cycles(np.array(lows[:-1], dtype=int), np.array(lows[1:], dtype=int))


def split_cycles(cycles: Cycles, min_fit: int = 2, min_held_out: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """Cycles to fit and cycles to hold out: alternating, the first cycle always fitted, so
    both sets span the whole test (drifts are seen by both).

    Raises:
        ValueError: when there are too few cycles to hold any out.
    """
    n = len(cycles)
    if n < min_fit + min_held_out:
        raise ValueError(
            f"found {n} stretch cycle(s); diagnosis needs at least {min_fit + min_held_out} "
            f"({min_fit} to fit, {min_held_out} to hold out)"
        )
    fit = np.arange(0, n, 2)
    held_out = np.arange(1, n, 2)
    return fit, held_out


def cycle_starts(elongation_m: np.ndarray) -> np.ndarray:
    """Indices of the samples where a cycle starts or ends: the crosshead back at zero
    elongation (the protocol's samples hit 0 exactly) after having moved away."""
    at_zero = np.flatnonzero(elongation_m <= 0.0)
    if at_zero.size < 2:
        raise ValueError("no complete cycle: the elongation returns to zero fewer than twice")
    # A hold at zero leaves runs of zeros: keep the last sample of each run.
    last_of_run = np.append(np.diff(at_zero) > 1, True)
    return at_zero[last_of_run]
