"""Does each named cause keep its gain when the build is as uncertain as it is?

A diagnosis takes the muscle's build as the experiment file declares it. No build is exactly as
declared, and the experiment says by how much it may not be: `[uncertain]` gives each build field
a tolerance (fiber_revolutions = 0.1, braid_angle_deg = 1.5, length_m = 0.001, ...); without it,
the braid's wind is free within 5 % of the declared revolutions (io.sections.DEFAULT_WIND_TOLERANCE:
the fibers' turns are counted by hand, the sleeve settles on its end fittings as it will). A few
percent of wind changes how the gas volume and the force follow the stretch, which a catalog
effect can mimic in part: on data from another team's model, whose braid kinematics differ from
pamkit's by about a 2.5 % wind, a 3.8 % crosshead scale was named a dead volume, and a 0.8-sample
fixture slack a pressure offset.

So the causes are fitted again with the uncertain fields free within their tolerances, beside the
leading cause's rivals and against a baseline calibrated with the same freedom, and judged by the
same rules (decide.py): each cause must keep a significant gain on the channels it changes over the
model without it, and the leading cause must still beat every credible rival on the same bootstrap
draws. A cause that fails either cannot be told from a build otherwise than declared, and the
diagnosis says so instead of naming it. A field that the refit drives to its tolerance's end is the
base model straining (reported), not a reason to refuse a cause that keeps its gain. A test whose
uncertain fields `[calibrate]` already fits, or whose `[uncertain]` section is empty (the build is
exact), needs no check.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from pamkit._core import EffectStage
from pamkit.diagnosis.calibrate import Fit, fit_baseline
from pamkit.diagnosis.candidates import fit_candidate, fit_pair
from pamkit.diagnosis.decide import MIN_GAIN, Cause, Judgement, Score, judge, keeps_gain, score
from pamkit.diagnosis.kinds import Problem
from pamkit.diagnosis.model import Predictor, uncertain_fields
from pamkit.io.sections import declared_value

# Significant candidates after the leading cause refitted beside it: the ones that could take its place.
RIVALS = 3


@dataclass
class BuildCheck:
    """The causes refitted with the build's uncertain fields free, and how many keep their gain."""

    causes: list[str]  # the labels of the causes named with the build as declared, in order
    fields: dict[str, tuple[float, float]]  # each uncertain field: (declared value, tolerance)
    baseline: Fit  # the baseline calibrated with the uncertain fields free
    fits: list[Fit]  # the models up to each cause, refitted there (fewer when a refit failed)
    own: list[Score]  # each cause's own gain there, over the model without it (credited)
    declared_gains: list[float]  # each cause's own credited gain with the build as declared
    kept: int  # the leading causes that keep a significant gain on their own channels there
    ahead: Judgement | None  # a credible rival the leading cause does not beat there on the same draws
    over_rival: float  # the lower end of the leading cause's paired gain over its closest credible rival there

    def at_bound(self) -> list[str]:
        """The uncertain fields that end at an end of their tolerance beside the causes: the base
        model straining. (The baseline alone may strain them to absorb what a cause explains.)"""
        return sorted(
            {
                name
                for fit in self.fits
                for name, (coordinate, x) in fit.coordinates.items()
                if name in self.fields and coordinate.at_bound(x) is not None
            }
        )

    def margin(self) -> float:
        """How far the check is from refusing, with the build free: the smallest of each cause's own
        credited gain over MIN_GAIN, the lower end of its interval, and the leading cause's paired
        margin over its closest credible rival (> 0 keeps them); -1 where a refit failed."""
        if not self.own:
            return -1.0
        own = min(min(s.credited_gain - MIN_GAIN, s.credited_ci95[0]) for s in self.own)
        return float(min(own, self.over_rival))

    def _freedom(self) -> str:
        return ", ".join(
            f"{name} {declared:.4g} ± {tolerance:.3g} (calibrated {self.baseline.params[name]:.4g})"
            for name, (declared, tolerance) in self.fields.items()
        )

    def objection(self) -> str:
        label = self.causes[self.kept]
        if self.ahead is not None:
            why = (
                f"{self.ahead.fit.name} explains the held-out units as well there (held-out gain "
                f"{self.ahead.score.combined_gain:.3f})"
            )
        elif self.kept >= len(self.own):
            why = "its refit failed"
        else:
            s = self.own[self.kept]
            why = (
                f"its held-out gain on the channels it changes falls to {s.credited_gain:.3f} "
                f"(95 % CI {s.credited_ci95[0]:.3f}–{s.credited_ci95[1]:.3f}), "
                f"from {self.declared_gains[self.kept]:.3f} with the build as declared"
            )
        return (
            f"with the build free within what the experiment declares ({self._freedom()}) {label} is no longer a "
            f"cause ({why}): the data do not tell it from a muscle built otherwise than declared"
        )

    def to_json(self) -> dict:
        with_causes = self.fits[-1].baseline_params if self.fits else {}
        return {
            "fields": {
                name: {
                    "declared": declared,
                    "tolerance": tolerance,
                    "calibrated": self.baseline.params[name],  # by the baseline alone
                    "calibrated_with_causes": with_causes.get(name),
                }
                for name, (declared, tolerance) in self.fields.items()
            },
            "at_bound": self.at_bound(),
            "causes": self.causes,
            "own_gain_there": [s.credited_gain for s in self.own],
            "own_gain_declared": self.declared_gains,
            "kept": self.causes[: self.kept],
            "ahead_there": self.ahead.fit.name if self.ahead is not None else None,
            "margin": self.margin(),
            "survives": self.kept == len(self.causes),
        }


def _refit(problem: Problem, baseline: Fit, label: str, factory, seed: int) -> Fit:
    """One candidate fitted as the diagnosis fits it: an instrument first on the calibrated
    baseline, then with the baseline free, the one that gains more kept (as engine.py does)."""
    fit = fit_candidate(problem, baseline, factory, label)
    if fit.error is not None or fit.effects[0].stage() != EffectStage.measurement:
        return fit
    refit = fit_candidate(problem, baseline, factory, label, fit)
    if refit.error is not None:
        return fit
    gains = [score(problem, baseline, f, np.random.default_rng(seed)).combined_gain for f in (fit, refit)]
    return refit if gains[1] > gains[0] else fit


def check_build(
    problem: Problem, causes: list[Cause], judged: list[Judgement], factories: dict, seed: int, pool
) -> BuildCheck | None:
    """The `causes` (decide.Cause, the leading one first) refitted with the build's uncertain
    fields free, each beside those before it, and the RIVALS significant candidates that follow
    the leading cause in `judged`, all judged by decide.py's rules against a baseline calibrated
    with the same freedom; None where nothing of the build is uncertain and not already fitted.
    `pool` runs the refits (a concurrent.futures executor)."""
    experiment = problem.experiment
    names = uncertain_fields(experiment)
    if not names:
        return None
    fields = {
        name: (declared_value(name, experiment.build, experiment.bladder), experiment.uncertain[name]) for name in names
    }
    windy = replace(problem, predictor=Predictor(experiment, problem.channels, uncertain=True))
    baseline = fit_baseline(windy)
    labels = [c.label for c in causes]
    rivals = [j.fit.name for j in judged if j.significant and j.fit.name not in labels][:RIVALS]
    singles = [pool.submit(_refit, windy, baseline, label, factories[label], seed) for label in [labels[0], *rivals]]
    first, *others = [f.result() for f in singles]
    fits: list[Fit] = []
    own: list[Score] = []
    previous = baseline
    for k, label in enumerate(labels):
        fit = (
            first
            if k == 0
            else fit_pair(windy, previous, factories[labels[0]], factories[label], "+".join(labels[: k + 1]))
        )
        if fit.error is not None:
            break
        fits.append(fit)
        own.append(score(windy, previous, fit, np.random.default_rng(seed), credit=fit.effects[k:]))
        previous = fit
    there = [
        judge(windy, f, score(windy, baseline, f, np.random.default_rng(seed)), baseline)
        for f in others
        if f.error is None
    ]
    # The leading cause against each credible rival there, on the same bootstrap draws (rule 6).
    ahead, over_rival = None, np.inf
    if own:
        mine = score(windy, baseline, fits[0], np.random.default_rng(seed)).combined_samples
        for j in sorted(there, key=lambda j: -j.score.combined_gain):
            if j.significant and j.credible:
                low = float(np.percentile(mine - j.score.combined_samples, 2.5))
                over_rival = min(over_rival, low)
                if low <= 0.0 and ahead is None:
                    ahead = j
    kept = 0
    if ahead is None:
        for gained in own:
            if not keeps_gain(gained):
                break
            kept += 1
    declared = [c.own.credited_gain for c in causes]
    return BuildCheck(labels, fields, baseline, fits, own, declared, kept, ahead, over_rival)
