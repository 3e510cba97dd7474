"""Glitches: single samples a real rig's channel throws far off its course (a stray ADC read, a
burst of line noise decoded as a value, a load cell's connector), which no model of the muscle
or of its instruments explains. Left in, one such sample in a few thousand makes a null
`unexplained` and costs a cause its gain; so a time series' isolated glitches are found before
the diagnosis and their rows left out, with a note saying where.

A sample is a glitch on a channel the model predicts when it stands out both ways at once:
beyond both its neighbours, and off the straight line through the three samples on either side
(less the line's own miss on a curved stretch), each by more than GLITCH_SIGMAS times the
channel's noise. A turning point (a force peaking where the crosshead turns, then stepping down
with its friction) stays on one side's line, a step between its neighbours; neither is a glitch.
Samples where an input turns (the crosshead's elongation, a supplied test's pressure) and their
neighbours are never one: a friction's step there can leave the turning sample off both lines.
A supplied test's pressure drives the model: its glitch is a sample off its course by the same
rule where the force does not follow it.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from pamkit._core import GasMode
from pamkit.diagnosis.evidence import noise_scale
from pamkit.io.columns import file_name
from pamkit.io.experiment import Experiment

#: How far off, in its channel's noise, a sample must stand to be a glitch. The benches' and the
#: independent generators' data (1315 channels: pamkit's synthetic tests, its mismatched builds,
#: the near-model world, the bundled examples) stand at most 6.9 (a quantised thermometer's count
#: toggling); a stray read stands tens to hundreds.
GLITCH_SIGMAS = 12.0

#: The channels searched: what the model predicts and the data measure (a supplied test's pressure
#: drives the model: an input, whose glitch is one the force does not follow).
SEARCHED = ("force_N", "gauge_pressure_Pa", "temperature_K")


class GlitchWarning(UserWarning):
    """Samples of a time series were left out as glitches; the message says which."""


def off_course(values: np.ndarray, sigma: float) -> np.ndarray:
    """How far each sample stands off its course, in `sigma`: the smaller of its distance beyond
    both neighbours and its distance from each side's line through three samples, that line's
    miss on a curved stretch (twice the three samples' second difference; a parabola's is 5/3 of
    it) taken off. Zero within four samples of an end."""
    x = np.asarray(values, dtype=float)
    ratio = np.zeros(x.size)
    if x.size < 9:
        return ratio

    def at(offset: int) -> np.ndarray:  # each sample's neighbour `offset` away, as a view
        return x[4 + offset : x.size - 4 + offset]

    centre = at(0)
    beyond = np.abs(centre - np.clip(centre, np.minimum(at(-1), at(1)), np.maximum(at(-1), at(1))))
    off = np.full(centre.shape, np.inf)
    for near, middle, far in ((-1, -2, -3), (1, 2, 3)):
        slope = (at(near) - at(far)) / (near - far)
        line = (at(near) + at(middle) + at(far)) / 3.0 - slope * middle
        curve = np.abs(at(near) - 2.0 * at(middle) + at(far))
        off = np.minimum(off, np.abs(centre - line) - 2.0 * curve)
    ratio[4:-4] = np.maximum(np.minimum(beyond, off), 0.0) / sigma
    return ratio


#: The share of its larger step by which an input's step must change for it to turn there (a
#: crosshead reversing changes it by twice, stopping by all of it; a logger's jittered stamps on
#: a ramp by a few per cent).
TURN_SHARE = 0.25


def turning(values: np.ndarray) -> np.ndarray:
    """Samples where an input turns, and their neighbours: where its step changes by more than
    TURN_SHARE of the larger of its steps on either side and by more than GLITCH_SIGMAS times
    its noise."""
    u = np.asarray(values, dtype=float)
    step = np.diff(u)
    change = np.abs(np.diff(step))
    larger = np.maximum(np.abs(step[1:]), np.abs(step[:-1]))
    turns = np.zeros(u.size, dtype=bool)
    turns[1:-1] = (change > TURN_SHARE * larger) & (change > GLITCH_SIGMAS * noise_scale(u))
    return turns | np.roll(turns, 1) | np.roll(turns, -1)


#: How far off its course, in its noise, the force stands where it follows a supplied pressure's
#: jump: a pressure that really jumped moves the force by its area, some tenths of a newton a
#: kilopascal, several times the force's noise wherever the pressure's jump is a glitch's size.
FOLLOWS_SIGMAS = 3.0


def without_glitches(experiment: Experiment) -> tuple[Experiment, dict | None]:
    """The time series without its glitches' rows (the module docstring's rule), and a note of
    them for the report's warnings and its verdict (None when there is none)."""
    columns = experiment.columns
    course = {c: off_course(columns[c], noise_scale(columns[c])) for c in SEARCHED if c in columns}
    crosshead = turning(columns["elongation_m"])
    ratios: dict[str, np.ndarray]
    if experiment.gas == GasMode.supplied:
        turns = crosshead | turning(columns["gauge_pressure_Pa"])
        ratios = {c: np.where(turns, 0.0, r) for c, r in course.items() if c != "gauge_pressure_Pa"}
        if "force_N" in course:
            # The pressure drives the model: its glitch is a sample the force does not follow,
            # a transducer's, which would drive the model to a force the muscle never made.
            followed = crosshead | (course["force_N"] > FOLLOWS_SIGMAS)
            ratios["gauge_pressure_Pa"] = np.where(followed, 0.0, course["gauge_pressure_Pa"])
    else:
        ratios = {c: np.where(crosshead, 0.0, r) for c, r in course.items()}
    found = {c: rows for c, ratio in ratios.items() if (rows := np.flatnonzero(ratio > GLITCH_SIGMAS)).size}
    if not found:
        return experiment, None
    glitched = np.zeros(experiment.time_s.size, dtype=bool)
    for rows in found.values():
        glitched[rows] = True
    kept = replace(experiment, columns={name: values[~glitched].copy() for name, values in columns.items()})
    sizes = np.concatenate([ratios[channel][rows] for channel, rows in found.items()])
    where = "; ".join(
        f"{file_name(channel)} at {', '.join(f'{experiment.time_s[r]:.6g}' for r in rows)} s"
        for channel, rows in found.items()
    )
    sentence = (
        f"{int(glitched.sum())} isolated sample(s) left out as glitches, {sizes.min():.0f}-{sizes.max():.0f}x "
        f"the noise off the samples beside them ({where})"
    )
    note = {
        "glitches": sentence,
        "rows_left_out": int(glitched.sum()),
        "time_s": {channel: [float(experiment.time_s[r]) for r in rows] for channel, rows in found.items()},
        "values": {channel: [float(columns[channel][r]) for r in rows] for channel, rows in found.items()},
        "glitch_over_noise": {channel: [float(v) for v in ratios[channel][rows]] for channel, rows in found.items()},
    }
    return kept, note
