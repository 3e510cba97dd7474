"""The crosshead's programmed motion behind its measured displacement.

A tensile machine runs straight ramps and holds; its encoder adds a few micrometres of noise.
Simulating the noisy samples as they are puts a kink in the elongation rate at every sample,
and every state that follows the rate (the bladder's viscous stresses, the gas temperature)
then forces the integrator to tiny steps. Diagnosis simulates the programmed motion instead:
straight lines fitted between the turning points, meeting at corners placed where the lines
cross, kept only when the measured samples lie on it to within their noise.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pamkit.diagnosis.evidence import noise_scale
from pamkit.diagnosis.filters import savgol_filter

STILL = 0.25  # a sample whose smoothed rate is below this share of the largest is holding
SMOOTHING = 9  # samples in the window that smooths the rate
ACCEPT_NOISE = 3.0  # the fit is used if the samples scatter around it by less than this many noise sigmas
ACCEPT_FLOOR_M = 2e-6  # ... or by less than this (an encoder's few micrometres)
SNAP = 0.05  # a corner this close to a sample, in sample intervals, is put on it


@dataclass(frozen=True)
class Motion:
    """A piecewise-linear crosshead motion: knots (corners included) and where the measured
    samples sit among them."""

    time_s: np.ndarray
    elongation_m: np.ndarray
    sample_rows: np.ndarray  # index of each measured sample in time_s


def _runs(kind: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Start and end (exclusive) of each run of equal values."""
    starts = np.flatnonzero(np.concatenate([[True], kind[1:] != kind[:-1]]))
    return starts, np.concatenate([starts[1:], [kind.size]])


def measured_motion(time: np.ndarray, elongation: np.ndarray) -> Motion:
    return Motion(np.asarray(time, float), np.asarray(elongation, float), np.arange(len(time)))


def programmed_motion(time: np.ndarray, elongation: np.ndarray) -> Motion:
    """Straight ramps and holds fitted to the measured crosshead, or the measurement itself when
    it is not made of them (see the module docstring)."""
    time = np.asarray(time, float)
    elongation = np.asarray(elongation, float)
    if time.size < 2 * SMOOTHING:
        return measured_motion(time, elongation)
    rate = np.gradient(savgol_filter(elongation, SMOOTHING, 2), time)
    largest = float(np.max(np.abs(rate)))
    if largest == 0.0:
        return measured_motion(time, elongation)
    kind = np.where(rate > STILL * largest, 1, np.where(rate < -STILL * largest, -1, 0))
    starts, ends = _runs(kind)
    # The smoothed rate passes through zero at a V-shaped turning point: a "hold" shorter than
    # the smoothing window between two ramps is that, and its samples go to the ramps.
    for start, end in zip(starts, ends):
        if kind[start] == 0 and end - start < SMOOTHING and start > 0 and end < time.size:
            middle = (start + end) // 2
            kind[start:middle] = kind[start - 1]
            kind[middle:end] = kind[end]
    starts, ends = _runs(kind)
    lines = []  # (slope, intercept) of each run of one kind
    edge = SMOOTHING // 2 + 1  # samples at a run's ends that the smoothing blurs into the next run
    for start, end in zip(starts, ends):
        if end - start > 2 * edge + 2:
            start, end = start + edge, end - edge
        t, e = time[start:end], elongation[start:end]
        if kind[start] == 0 or t.size < 2:
            lines.append((0.0, float(np.mean(e))))
        else:
            slope, intercept = np.polyfit(t, e, 1)
            lines.append((float(slope), float(intercept)))
    # Corners where consecutive lines cross, kept inside the span between the runs' middles.
    corners = []
    interval = float(np.median(np.diff(time)))
    for i in range(len(lines) - 1):
        (a1, b1), (a2, b2) = lines[i], lines[i + 1]
        low, high = time[(starts[i] + ends[i] - 1) // 2], time[(starts[i + 1] + ends[i + 1] - 1) // 2]
        crossing = float(np.clip((b2 - b1) / (a1 - a2) if a1 != a2 else 0.5 * (low + high), low, high))
        # A corner within a twentieth of a sample interval of a sample is on it (a machine that
        # turns on its own sample clock): moving it by the fit's scatter would only change
        # which way the sample itself counts as moving.
        nearest = time[np.argmin(np.abs(time - crossing))]
        corners.append(float(nearest) if abs(nearest - crossing) < SNAP * interval else crossing)
    segment = np.searchsorted(np.asarray(corners), time, side="right")
    fitted = np.array([lines[k][0] * t + lines[k][1] for k, t in zip(segment, time)])
    scatter = float(np.sqrt(np.mean((elongation - fitted) ** 2)))
    if scatter > max(ACCEPT_NOISE * noise_scale(elongation), ACCEPT_FLOOR_M):
        return measured_motion(time, elongation)
    # The knots: every sample on its line, and the corners on both lines at once.
    corner_e = [lines[i][0] * c + lines[i][1] for i, c in enumerate(corners)]
    all_t = np.concatenate([time, corners])
    all_e = np.concatenate([fitted, corner_e])
    order = np.argsort(all_t, kind="stable")
    all_t, all_e = all_t[order], all_e[order]
    keep = np.concatenate([[True], np.diff(all_t) > 1e-9 * max(1.0, abs(all_t[-1]))])
    rows = np.searchsorted(all_t[keep], time)
    return Motion(all_t[keep], all_e[keep], rows)


def with_knots_after_turns(motion: Motion, travel_m: float, subdivisions: int) -> tuple[Motion, np.ndarray]:
    """`motion` with each segment within `travel_m` of crosshead travel after a turn (a change of
    direction, a hold's end) cut into `subdivisions` equal ones: where a play between crosshead and
    muscle is taken up inside one sample interval, the muscle's own motion has a corner that the
    samples' straight lines would smear over the interval (its rate, so the friction, wrong there).
    Returns the refined motion (its sample_rows among the new knots) and the row of each of
    `motion`'s knots in it."""
    time, elongation = motion.time_s, motion.elongation_m
    step = np.diff(elongation)
    direction = np.sign(step)
    refine = np.zeros(step.size, dtype=bool)
    last, travelled = 0.0, np.inf
    for k, (d, s) in enumerate(zip(direction, step)):
        if d != 0 and d != last:
            travelled = 0.0
        if d != 0:
            last = d
        if travelled < travel_m:
            refine[k] = d != 0
            travelled += abs(s)
    fractions = np.arange(1, subdivisions) / subdivisions
    inserted_t = (time[:-1][refine, None] + np.diff(time)[refine, None] * fractions).ravel()
    inserted_e = (elongation[:-1][refine, None] + step[refine, None] * fractions).ravel()
    all_t = np.concatenate([time, inserted_t])
    order = np.argsort(all_t, kind="stable")
    rows = np.argsort(order)[: time.size]  # where each of motion's knots went
    refined = Motion(all_t[order], np.concatenate([elongation, inserted_e])[order], rows[motion.sample_rows])
    return refined, rows
