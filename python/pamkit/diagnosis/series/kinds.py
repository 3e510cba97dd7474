"""What was measured and what is held out.

The unit a diagnosis fits on and holds out follows the test: the stretch cycles of a cyclic
test, the pressurise/vent sweeps of a supplied-pressure test whose length the rig holds
(isometric), or, with fewer than four sweeps, their pressure plateaus. The units are found from
the commanded signal's structure — the crosshead's elongation, or the supplied pressure when the
length is held — never from noise: a held length's encoder noise has no cycles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from pamkit._core import Effect, GasMode, deflated_braid_angle_deg
from pamkit.diagnosis import evidence
from pamkit.diagnosis.coordinates import Coordinate, effect_space
from pamkit.diagnosis.cycles import Cycles, find_cycles, split_cycles
from pamkit.diagnosis.filters import running_median
from pamkit.diagnosis.series.model import Predictor
from pamkit.io.columns import value_from_si
from pamkit.io.experiment import Experiment
from pamkit.io.guards import ExperimentError
from pamkit.io.series import check_units
from pamkit.units import MILLIMETRE_PER_METRE

# A plateau of a stepped sweep starts where the pressure leaves the last one's level by more
# than this many noise sigmas, or this share of the sweep's span, whichever is larger; pieces
# shorter than PLATEAU_MERGE of the median piece (a transition's crossings) join the next.
PLATEAU_NOISE = 10.0
PLATEAU_SPAN = 0.05
PLATEAU_MERGE = 0.25
# A length counts as held when its whole travel is within this many noise sigmas of the
# encoder (Gaussian noise over 10^4 samples spans about 8 sigma peak to peak).
HELD_TRAVEL_NOISE = 20.0


# The instruments' readings at nothing, by the effect that carries one: (its channel, its
# parameter). A zero run reads them directly; on its zeroed data such an offset, fitted again,
# could only take a share of another misfit (the near-model world's load cell, strong seed 9, with
# a zero run beside it: zeroed of its true -10 N, refitted at -23 N beside the membrane's scale at
# its bound 0, the muscle's membrane law not the model's).
ZERO_RUN_MEASURES = {"load_cell": ("force_N", "offset_N"), "sensor_offset": ("gauge_pressure_Pa", "offset_Pa")}


@dataclass
class Problem:
    """What the fits share: data, noise scales, the units fitted and held out."""

    experiment: Experiment
    channels: list[str]
    measured: dict[str, np.ndarray]
    sigma: dict[str, float]
    fit_mask: np.ndarray
    held_mask: np.ndarray
    half_cycle: np.ndarray  # the bootstrap's unit: half a cycle (stretch / return, pressurise / vent)
    cycle: np.ndarray  # cycle number of every sample, -1 outside any
    unit_name: str  # what a unit is here: "stretch cycle", "pressurise/vent sweep", "pressure plateau"
    predictor: Predictor
    # the rows of the fitted and held-out units and the data there, taken once: a diagnosis
    # evaluates chi some 10^3 times on the same two masks
    _masked: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    # the measured channels each effect on the physics or the motion moves in this test, as its fit
    # found them (candidates.note_moved_channels): its gain is credited there (score.credited_channels)
    moved_channels: dict[str, list[str]] = field(default_factory=dict, init=False, repr=False, compare=False)

    def _rows_and_measured(self, mask: np.ndarray) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        kept = self._masked.get(id(mask))
        if kept is not None and kept[0] is mask:
            return kept[1], kept[2]
        rows = np.flatnonzero(mask)
        measured = {c: self.measured[c].take(rows) for c in self.channels}
        if mask is self.fit_mask or mask is self.held_mask:
            self._masked[id(mask)] = (mask, rows, measured)
        return rows, measured

    def chi(self, predicted: dict[str, np.ndarray], mask: np.ndarray) -> np.ndarray:
        rows, measured = self._rows_and_measured(mask)
        return np.concatenate(
            [(np.asarray(predicted[c]).take(rows) - measured[c]) / self.sigma[c] for c in self.channels]
        )

    def residual_units(self) -> np.ndarray:
        """The half cycle of each entry of `chi(..., fit_mask)`: the clusters of its intervals."""
        return np.tile(self.half_cycle[self.fit_mask], len(self.channels))

    def search_space(self, effect: Effect) -> list[Coordinate]:
        """An effect's fit coordinates in this test: effect_space's, less an instrument's reading at
        nothing that the test's zero run measured and took off the data (ZERO_RUN_MEASURES), which
        is held at zero."""
        measured = ZERO_RUN_MEASURES.get(effect.name())
        held = measured[1] if measured is not None and measured[0] in self.experiment.zeroed else None
        return [c for c in effect_space(effect) if c.name != held]

    def chi2_by_channel(self, predicted: dict[str, np.ndarray]) -> dict[str, float]:
        """Sum of squared noise-weighted residuals per channel on the fitted units."""
        rows, measured = self._rows_and_measured(self.fit_mask)
        return {
            c: float(np.sum(((np.asarray(predicted[c]).take(rows) - measured[c]) / self.sigma[c]) ** 2))
            for c in self.channels
        }


# The measured pressure at the start of a sealed test may differ from the declared inflation
# pressure by the transducer's calibration error (sensor_offset's plausible 12 kPa and 7 % gain)
# and the 5 % tolerance the baseline allows; beyond both it is a different test.
INFLATION_MISMATCH_PA = 25e3
INFLATION_MISMATCH_FRACTION = 0.25
# arctan(sqrt(2)): a braid at this angle neither contracts nor extends under pressure.
LOCKING_ANGLE_DEG = math.degrees(math.atan(math.sqrt(2.0)))
# A stretch test sampled every 5 s or slower whose crosshead never exceeds 0.1 mm/s while it
# travels more than a millimetre most likely counts milliseconds: bench tests sample at 5-1000 Hz
# and stretch at 2.5-50 mm/s (thesis section 3.2.1), which a millisecond column shows as one
# sample per 1-200 s and 2.5-50 um/s.
SLOW_SAMPLE_INTERVAL_S = 5.0
SLOWEST_STRETCH_M_PER_S = 100e-6
SMALLEST_TRAVEL_M = 1e-3


def check_consistency(experiment: Experiment) -> None:
    """Raises ExperimentError when the data contradict the declared test before anything is
    fitted: a sealed test whose pressure is its inflation pressure neither at its start nor at its
    rest in the first cycle, a time column that counts milliseconds, a braid wound past its locking
    angle."""
    angle = deflated_braid_angle_deg(experiment.build)
    if angle >= LOCKING_ANGLE_DEG:
        raise ExperimentError(
            f"{experiment.path}: [muscle] gives a deflated braid angle of {angle:.1f} deg, past the locking angle "
            f"{LOCKING_ANGLE_DEG:.1f} deg: such a braid lengthens when pressurised. Check fiber_revolutions (turns "
            "over the whole length, not per unit length) or braid_angle_deg"
        )
    time, elongation = experiment.time_s, experiment.elongation_m
    interval = float(np.median(np.diff(time)))
    fastest = float(np.max(np.abs(np.diff(elongation)) / np.diff(time)))
    if (
        interval >= SLOW_SAMPLE_INTERVAL_S
        and np.ptp(elongation) > SMALLEST_TRAVEL_M
        and fastest < SLOWEST_STRETCH_M_PER_S
    ):
        raise ExperimentError(
            f"{experiment.data_path}: one sample per {interval:g} s and a crosshead never faster than "
            f"{fastest * 1e6:.2g} um/s over {np.ptp(elongation) * MILLIMETRE_PER_METRE:.3g} mm of travel: is the time "
            "column in "
            "milliseconds? (time_s is in seconds)"
        )
    if experiment.gas != GasMode.sealed or "gauge_pressure_Pa" not in experiment.columns:
        return
    pressure = experiment.columns["gauge_pressure_Pa"]
    start = float(np.median(pressure[:5]))
    rest = float(np.min(pressure[: first_cycle_end(elongation)]))
    declared = experiment.inflation_gauge_pressure_Pa
    tolerance = max(INFLATION_MISMATCH_PA, INFLATION_MISMATCH_FRACTION * declared)
    # The first samples, or the lowest pressure of the first cycle: a sealed muscle is at its
    # inflation pressure whenever it is back at zero elongation, and a pressure logged late or early
    # (a time skew, which the diagnosis may name) passes through that rest within the first cycle.
    if abs(start - declared) > tolerance and abs(rest - declared) > tolerance:
        start_kPa, rest_kPa, declared_kPa = (value_from_si("gauge_pressure_Pa", p) for p in (start, rest, declared))
        raise ExperimentError(
            f"{experiment.path}: [test] inflation_pressure_kPa = {declared_kPa:g}, but the data start at "
            f"{start_kPa:.1f} kPa and rest at {rest_kPa:.1f} kPa in their first cycle ({experiment.data_path}): the "
            "declared test and the measured one differ; correct the inflation pressure (or the pressure "
            "column's unit) before diagnosing"
        )


def first_cycle_end(elongation: np.ndarray) -> int:
    """The row where the first stretch has returned to rest (within a tenth of the travel), or the
    whole record if it never does."""
    low, span = float(np.min(elongation)), float(np.ptp(elongation))
    if span <= 0.0:
        return elongation.size
    stretched = np.flatnonzero(elongation > low + 0.5 * span)
    if stretched.size == 0:
        return elongation.size
    back = np.flatnonzero(elongation[stretched[0] :] < low + 0.1 * span)
    return int(stretched[0] + back[0] + 1) if back.size else elongation.size


def length_is_held(experiment: Experiment) -> bool:
    """Whether the rig holds the length: the elongation moves by no more than its own noise."""
    elongation = experiment.elongation_m
    return float(np.ptp(elongation)) <= HELD_TRAVEL_NOISE * evidence.noise_scale(elongation)


def driving_signal(experiment: Experiment) -> tuple[str, np.ndarray, str]:
    """The commanded signal whose cycles are the test's units: (column, values, unit name)."""
    if experiment.gas == GasMode.supplied and length_is_held(experiment):
        return "gauge_pressure_Pa", experiment.columns["gauge_pressure_Pa"], "pressurise/vent sweep"
    return "elongation_m", experiment.elongation_m, "stretch cycle"


def plateaus(signal: np.ndarray) -> Cycles:
    """The plateaus of a stepped sweep (each with the transition that leads to it), from the
    signal's levels: a new one starts where the median-smoothed signal leaves the current
    level by more than the larger of PLATEAU_NOISE noise sigmas and PLATEAU_SPAN of the span."""
    smooth = running_median(signal, 5)
    threshold = max(PLATEAU_NOISE * evidence.noise_scale(signal), PLATEAU_SPAN * float(np.ptp(smooth)))
    starts, level = [0], smooth[0]
    for k, value in enumerate(smooth):
        if abs(value - level) > threshold:
            starts.append(k)
            level = value
    bounds = starts + [smooth.size]
    lengths = np.diff(bounds)
    typical = float(np.median(lengths)) if lengths.size else 0.0
    kept = [start for start, length in zip(starts, lengths) if length >= PLATEAU_MERGE * typical or start == 0]
    return Cycles(np.array(kept, dtype=int), np.array(kept[1:] + [smooth.size], dtype=int))


def build_problem(experiment: Experiment) -> Problem:
    """The data, its noise and its units, checked.

    Raises:
        ExperimentError: for values in the wrong unit, no channel to compare, or too few units to
            hold any out (saying what would do).
    """
    check_units(experiment.data_path, experiment.columns)
    check_consistency(experiment)
    channels = experiment.measured()
    if experiment.gas == GasMode.supplied:
        channels = [c for c in channels if c != "gauge_pressure_Pa"]  # an input there, not a prediction
    if not channels:
        raise ExperimentError(
            f"{experiment.data_path}: no measured channel to compare with (needs force_N, pressure_kPa or "
            "temperature_C besides time_s and elongation_m)"
        )
    column, signal, unit_name = driving_signal(experiment)
    cycles: Cycles = find_cycles(signal)
    halves = cycles.half_cycle_index(signal)
    if len(cycles) < 4 and column == "gauge_pressure_Pa":
        # One or two sweeps: their pressure plateaus are the units (steps), each its own
        # bootstrap unit.
        cycles, unit_name = plateaus(signal), "pressure plateau"
        halves = cycles.index(signal.size)
    try:
        fit_cycles, held_cycles = split_cycles(cycles)
    except ValueError:
        raise ExperimentError(
            f"{experiment.data_path}: column {column}: found {len(cycles)} {unit_name}(s); diagnosis fits on some "
            f"and holds others out, so it needs at least 4 (2 to fit, 2 to hold out): record more {unit_name}s"
        ) from None
    cycle = cycles.index(signal.size)
    measured = {c: experiment.columns[c] for c in channels}
    sigma = {c: evidence.noise_scale(measured[c]) for c in channels}
    return Problem(
        experiment=experiment,
        channels=channels,
        measured=measured,
        sigma=sigma,
        fit_mask=np.isin(cycle, fit_cycles) & ~experiment.censored,
        held_mask=np.isin(cycle, held_cycles) & ~experiment.censored,
        half_cycle=halves,
        cycle=cycle,
        unit_name=unit_name,
        predictor=Predictor(experiment, channels),
    )
