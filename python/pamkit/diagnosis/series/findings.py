"""What a time series' fit's parameters say of it: the calibrated baseline's at a bound of their
search or outside their plausible range (coordinates.findings), and values below what one sample
resolves (a lag shorter than the sample interval, a slack shorter than the crosshead's travel
between samples)."""

from __future__ import annotations

import numpy as np

from pamkit._core import Resolution
from pamkit.diagnosis.coordinates import Finding, findings
from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.kinds import Problem


def sample_interval(problem: Problem) -> float:
    return float(np.median(np.diff(problem.experiment.time_s)))


def travel_per_sample(problem: Problem) -> float:
    steps = np.abs(np.diff(problem.experiment.elongation_m))
    moving = steps[steps > 0.1 * steps.max()] if steps.max() > 0 else steps
    return float(np.median(moving)) if moving.size else 0.0


def _resolution_limit(problem: Problem, resolution: Resolution) -> tuple[float, str]:
    # An effect smaller than one sample resolves mimics a sub-sample shift of the channels: a
    # clock drifting by 50 ppm over a 400 s test is 20 ms.
    if resolution == Resolution.sample_interval:
        return sample_interval(problem), "the sample interval"
    if resolution == Resolution.travel_per_sample:
        return travel_per_sample(problem), "the crosshead's travel between samples"
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
