"""A candidate's score against the calibrated baseline: held-out RMSE and gain per channel, their
bootstrap intervals over held-out half-cycles, the combined and the credited gain, the change of the
information criterion, and whether that is significant (series/decide.py, rule 1)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from pamkit._core import GasMode
from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.kinds import Problem
from pamkit.diagnosis.significance import BOOTSTRAP_SAMPLES, MIN_BIC_DROP, MIN_GAIN


@dataclass
class Score:
    rmse: dict[str, float]
    gain: dict[str, float]
    gain_ci95: dict[str, list[float]]
    combined_gain: float  # over every channel, each weighted by its noise
    combined_ci95: list[float]
    delta_bic: float
    credited_gain: float  # over the channels the fit's effects change only
    credited_ci95: list[float]
    # the combined gain on each bootstrap draw; every candidate's draws are the same units
    # (one seed), so two candidates' samples pair up
    combined_samples: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)


def _gain(sse_fit: float, sse_base: float) -> float:
    return float(1.0 - math.sqrt(sse_fit / sse_base)) if sse_base > 0 else 0.0


def credited_channels(problem: Problem, fit: Fit, effects=None) -> list[str]:
    """The measured channels `fit`'s effects (or `effects`, some of them) change: its gain is
    counted on these only. An instrument's are its own; an effect on the physics or the motion
    changes the channels its fit was seen to move in this test (candidates.note_moved_channels), or
    every channel where no fit of it has moved one."""
    effects = fit.effects if effects is None else effects
    changed = set()
    for effect in effects:
        named = effect.channels_changed() or problem.moved_channels.get(effect.name())
        changed.update(named if named else problem.channels)
        if problem.experiment.gas == GasMode.supplied and effect.reads_supplied_pressure():
            changed.add("force_N")  # its reading drives the model, so it acts on the force
    return [c for c in problem.channels if c in changed] if effects else list(problem.channels)


def score(problem: Problem, baseline: Fit, fit: Fit, rng: np.random.Generator, credit=None) -> Score:
    """Held-out RMSE per channel, gain against `baseline`, bootstrap intervals over held-out
    half-cycles, and the change of the Bayesian information criterion on the fitted cycles.
    Every candidate is ranked on every channel (the same yardstick, the same baseline freedom);
    the credited gain counts only the channels the fit's effects (or the effects `credit`, the
    ones `fit` adds to `baseline`) change."""
    units = np.unique(problem.half_cycle[problem.held_mask])
    sse_base = np.zeros((len(problem.channels), units.size))
    sse_fit = np.zeros_like(sse_base)
    counts = np.zeros(units.size)
    for j, unit in enumerate(units):
        mask = problem.held_mask & (problem.half_cycle == unit)
        counts[j] = mask.sum()
        for i, c in enumerate(problem.channels):
            sse_base[i, j] = np.sum((baseline.predicted[c] - problem.measured[c])[mask] ** 2)
            sse_fit[i, j] = np.sum((fit.predicted[c] - problem.measured[c])[mask] ** 2)
    credited = credited_channels(problem, fit, credit)
    weights = np.array([1.0 / problem.sigma[c] ** 2 for c in problem.channels])[:, None]
    credited_weights = np.array([1.0 / problem.sigma[c] ** 2 if c in credited else 0.0 for c in problem.channels])[
        :, None
    ]
    n = counts.sum()
    rmse = {c: float(np.sqrt(sse_fit[i].sum() / n)) for i, c in enumerate(problem.channels)}
    gain = {c: _gain(sse_fit[i].sum(), sse_base[i].sum()) for i, c in enumerate(problem.channels)}
    draws = rng.integers(0, units.size, size=(BOOTSTRAP_SAMPLES, units.size))
    boot_fit = sse_fit[:, draws].sum(axis=2)
    boot_base = sse_base[:, draws].sum(axis=2)
    gain_ci = {}
    for i, c in enumerate(problem.channels):
        gains = 1.0 - np.sqrt(boot_fit[i] / np.maximum(boot_base[i], 1e-300))
        gain_ci[c] = [float(np.percentile(gains, 2.5)), float(np.percentile(gains, 97.5))]

    def combined_with(w):
        boot = 1.0 - np.sqrt((w * boot_fit).sum(axis=0) / np.maximum((w * boot_base).sum(axis=0), 1e-300))
        return (
            _gain((w * sse_fit).sum(), (w * sse_base).sum()),
            [float(np.percentile(boot, 2.5)), float(np.percentile(boot, 97.5))],
            boot,
        )

    combined, combined_ci, samples = combined_with(weights)
    credited_gain, credited_ci, _ = combined_with(credited_weights)
    n_fit = int(problem.fit_mask.sum()) * len(problem.channels)
    delta_chi2 = sum(fit.training_chi2[c] - baseline.training_chi2[c] for c in problem.channels)
    delta_bic = delta_chi2 + (fit.parameter_count - baseline.parameter_count) * math.log(n_fit)
    return Score(rmse, gain, gain_ci, combined, combined_ci, float(delta_bic), credited_gain, credited_ci, samples)


def significant(s: Score) -> bool:
    return s.combined_gain >= MIN_GAIN and s.combined_ci95[0] > 0.0 and s.delta_bic < -MIN_BIC_DROP


def significance_margin(s: Score) -> float:
    """How far the weakest of the three significance tests is from its threshold, each in its
    own scale relative to the threshold (> 0: passes)."""
    return float(min(s.combined_gain - MIN_GAIN, s.combined_ci95[0], (-s.delta_bic - MIN_BIC_DROP) / MIN_BIC_DROP))
