"""What a time series' fit's parameters say of it: the calibrated baseline's at a bound of their
search or outside their plausible range (coordinates.findings), and values below what one sample
resolves (a lag shorter than 0.9 of the sample interval, a slack shorter than the crosshead's
travel between samples), a play that makes a channel it moves worse, and the values the data
place off their neutral ones."""

from __future__ import annotations

import math

import numpy as np

from pamkit._core import EffectStage, GasMode, Resolution
from pamkit.diagnosis.coordinates import Finding, findings
from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.kinds import Problem
from pamkit.diagnosis.series.model import PLAY_SUBDIVISIONS
from pamkit.diagnosis.series.score import credited_channels


def off_neutral(fit: Fit, effect, prefix: str) -> dict[str, bool]:
    """For each of `effect`'s parameters that has a neutral value and an interval in `fit` (keyed
    `prefix` + its name), whether that 95 % interval excludes the neutral value (a time constant's
    infinity too): the data place the effect there, not at nothing."""
    out = {}
    for p in effect.parameters():
        band = fit.intervals.get(prefix + p.name)
        if band is not None and not math.isnan(p.neutral):
            out[p.name] = not band[0] <= p.neutral <= band[1]
    return out


def sample_interval(problem: Problem) -> float:
    return float(np.median(np.diff(problem.experiment.time_s)))


def travel_per_sample(problem: Problem) -> float:
    steps = np.abs(np.diff(problem.experiment.elongation_m))
    moving = steps[steps > 0.1 * steps.max()] if steps.max() > 0 else steps
    return float(np.median(moving)) if moving.size else 0.0


# A shift in time (a skew, a lag) is resolved by the sampling from this share of one sample
# interval up. The sampling's own artefacts shift a channel by a fraction of an interval (a
# converter reading its channels in turn, an Arduino's channels 0.2-0.8 of an interval apart:
# bench_families; a clock drifting by 50 ppm over a 400 s test, 20 ms), while a record one whole
# sample off, a logger's commonest skew, is fitted within a few per cent of one sample where the
# base model is not exact (0.96-1.00 on the near-model bench, whose weakest skews and lags are one
# sample: at exactly one sample a fit a hair below it was refused, one a hair above named).
RESOLVED_SHARE_OF_SAMPLE = 0.9


def _resolution_limit(problem: Problem, resolution: Resolution) -> tuple[float, str]:
    if resolution == Resolution.sample_interval:
        limit = RESOLVED_SHARE_OF_SAMPLE * sample_interval(problem)
        return limit, f"{RESOLVED_SHARE_OF_SAMPLE:g} of the sample interval"
    if resolution == Resolution.travel_per_sample:
        # A sealed test's runs with a play follow the crosshead on knots PLAY_SUBDIVISIONS times
        # finer than the samples after each turn (model.py): a play shorter than one sample's travel
        # is modelled as it acts, down to one knot's travel. A supplied test is evaluated at its
        # samples alone.
        if problem.experiment.gas != GasMode.sealed:
            return travel_per_sample(problem), "the crosshead's travel between samples"
        return (
            travel_per_sample(problem) / PLAY_SUBDIVISIONS,
            f"the travel between the knots its runs follow ({PLAY_SUBDIVISIONS} between samples)",
        )
    return 0.0, ""


def baseline_findings(baseline: Fit) -> list[Finding]:
    """The calibrated baseline's parameters at a bound or implausible, less those the data do not
    determine (a friction scale in a test that never moves: where it ends says nothing of the
    model; it is reported among the undetermined values instead)."""
    return [f for f in findings(baseline) if f.parameter not in getattr(baseline, "undetermined", {})]


def _below_resolution(problem: Problem, fit: Fit):
    """(name, value, limit, what) of each parameter whose fitted size is below what one sample
    resolves."""
    for effect in fit.effects:
        prefix = f"{effect.name()}." if len(fit.effects) > 1 else ""
        for p in effect.parameters():
            limit, what = _resolution_limit(problem, p.resolution)
            value = fit.params.get(prefix + p.name)
            if limit > 0 and value is not None and abs(value) < limit:
                yield prefix + p.name, value, limit, what


def unresolved(problem: Problem, fit: Fit) -> list[str]:
    """Parameters whose fitted size is below what one sample resolves, as sentences."""
    return [
        f"{name} = {value:.3g} is below {what} ({limit:.3g})"
        for name, value, limit, what in _below_resolution(problem, fit)
    ]


def within_resolution(problem: Problem, fit: Fit) -> bool:
    """Whether every parameter found below what one sample resolves has a 95 % interval that reaches
    one sample: the data do not place it below (a lag of one sample fitted at 0.0499 s for a 0.05 s
    interval). Such a fit is no sampling artefact to pass over, but a rival."""
    below = list(_below_resolution(problem, fit))
    return bool(below) and all(
        name in fit.intervals and max(abs(end) for end in fit.intervals[name]) >= limit for name, _, limit, _ in below
    )


def sub_sample_play(problem: Problem, fit: Fit) -> bool:
    """Whether `fit` holds a play (a parameter the crosshead's travel resolves) shorter than the
    crosshead's travel between two samples."""
    plays = [
        (f"{e.name()}." if len(fit.effects) > 1 else "") + p.name
        for e in fit.effects
        for p in e.parameters()
        if p.resolution == Resolution.travel_per_sample
    ]
    return bool(plays) and any(abs(fit.params[name]) < travel_per_sample(problem) for name in plays)


def mimicked_by_a_shift(problem: Problem, candidate, judged: list) -> list[str]:
    """Why a play shorter than one sample's travel is not told from the sampling: it changes the
    samples just after each turn, as a channel shifted by less than one sample does (a logger's
    clock merged with the machine's). Where such a shift (a significant candidate whose time is
    below what the sampling resolves) explains the held-out units as well on the same draws, the
    play is no cause. Judgements are decide.py's."""
    if not sub_sample_play(problem, candidate.fit):
        return []
    for rival in judged:
        shifts = any(p.resolution == Resolution.sample_interval for e in rival.fit.effects for p in e.parameters())
        if rival is candidate or not (rival.significant and shifts and rival.below_resolution):
            continue
        low, high = np.percentile(candidate.score.combined_samples - rival.score.combined_samples, [2.5, 97.5])
        if low <= 0.0:
            return [
                f"{rival.fit.name}, a shift below one sample, explains the held-out units as well (gain "
                f"{rival.score.combined_gain:.3f} against {candidate.score.combined_gain:.3f}; the difference's 95 % "
                f"interval [{low:.3f}, {high:.3f}] holds zero): a play shorter than one sample's travel "
                f"({travel_per_sample(problem):.3g} m) is not told from it"
            ]
    return []


def moves_against(problem: Problem, candidate) -> list[str]:
    """Why an effect on the muscle's motion (a fixture's play) that makes a channel it moves worse
    is no such effect: the muscle's length drives the force and the gas alike, so a play that is the
    muscle's does not trade one channel it moves for another, and one that does is fitting one
    channel's timing (a logger's skew of the pressure read as a play: bench_families subsample_skew
    seed 10, the force's gain -0.33 for the pressure's 0.53). Over the near-model bench's seeds 1-30
    every play named right gained on the force (0.02-0.90). A candidate is decide.py's Judgement."""
    if not any(e.stage() == EffectStage.motion for e in candidate.fit.effects):
        return []
    s = candidate.score
    moved = credited_channels(problem, candidate.fit)
    worse = [c for c in moved if s.gain_ci95[c][1] < 0.0]
    if not worse:
        return []
    better = [c for c in moved if c not in worse]
    return [
        f"it makes {', '.join(f'{c} worse (gain {s.gain[c]:.2f})' for c in worse)}"
        + (f" for {', '.join(f'{c} (gain {s.gain[c]:.2f})' for c in better)}" if better else "")
        + ": the muscle's motion moves every channel it drives alike, so what it explains is one "
        "channel's timing, not the muscle's"
    ]
