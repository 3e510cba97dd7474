"""Does the named cause survive the build's own uncertainty?

A diagnosis takes the muscle's build as the experiment file declares it. The number a builder
knows least well is the braid's wind: the fibers' turns over the braided length, counted by hand,
and the angle the sleeve settles at on its end fittings. A few percent of wind changes how the gas
volume and the force follow the stretch, which a catalog effect can mimic in part: on data from
another team's model, whose braid kinematics differ from pamkit's by about a 2.5 % wind, a 3.8 %
crosshead scale was named a dead volume, and a 0.8-sample fixture slack a pressure offset.

So a named cause is fitted again with the wind free within its tolerance (model.WIND_TOLERANCE),
beside its leading rivals and against a baseline calibrated with the same freedom, and judged by
the same rules (decide.py). A cause that no longer leads there — not significant, or another
candidate explains more, or as much on the same bootstrap draws — cannot be told from a braid
wound otherwise than declared: the diagnosis says so instead of naming it. A `[calibrate]` table
that already declares the wind or the braid angle unknown needs no check (the baseline fits it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from pamkit._core import EffectStage
from pamkit.diagnosis.calibrate import Fit, fit_baseline
from pamkit.diagnosis.candidates import fit_candidate, fit_pair
from pamkit.diagnosis.decide import Judgement, attainable_gain, judge, score, significance_margin
from pamkit.diagnosis.kinds import Problem
from pamkit.diagnosis.model import WIND_TOLERANCE, Predictor, winds_declared

WIND = "fiber_revolutions"
# Significant candidates after the named cause refitted beside it: the ones that could take its place.
RIVALS = 3


@dataclass
class BuildCheck:
    """The named cause and its leading rivals refitted with the braid's wind free, and whether
    the cause still leads there."""

    named: str  # the label of the cause named with the build as declared
    declared: float  # the declared fiber revolutions
    baseline: Fit  # the baseline calibrated with the wind free
    there: list[Judgement]  # the refitted candidates, judged against that baseline, best first
    mine: Judgement | None  # the named cause among them (None: its refit failed)

    @property
    def wind(self) -> float:
        """The wind the baseline calibrates with it free."""
        return self.baseline.params[WIND]

    @property
    def best(self) -> Judgement | None:
        """The best significant refit."""
        return next((j for j in self.there if j.significant), None)

    @property
    def rival(self) -> Judgement | None:
        """The best significant, credible refit other than the cause."""
        return next((j for j in self.there if j is not self.mine and j.significant and j.credible), None)

    def over_rival(self) -> float:
        """The lower end of the 95 % interval of the cause's paired gain over the rival (decide.py,
        rule 6); inf without a rival."""
        if self.rival is None or self.mine is None:
            return math.inf
        return float(np.percentile(self.mine.score.combined_samples - self.rival.score.combined_samples, 2.5))

    @property
    def survives(self) -> bool:
        """The cause still leads: the best significant candidate, ahead of every credible rival on
        the same draws. Its own parameters' credibility is not asked again: the extra freedom may
        move them, but that is no sign the wind explains the data instead."""
        return self.mine is not None and self.best is self.mine and self.over_rival() > 0.0

    def margin(self) -> float:
        """The cause's significance margin with the wind free (decide.significance_margin, > 0
        passes) or its margin over the rival there, the smaller; -1 where it does not survive."""
        if not self.survives:
            return -1.0
        return float(min(significance_margin(self.mine.score), self.over_rival()))

    def objection(self) -> str:
        if self.mine is None:
            why = "its refit failed"
        elif not self.mine.significant:
            why = f"its held-out gain is {self.mine.score.combined_gain:.3f}"
        elif self.best is not self.mine:
            why = f"{self.best.fit.name} explains more (held-out gain {self.best.score.combined_gain:.3f})"
        else:
            why = f"{self.rival.fit.name} explains as much (held-out gain {self.rival.score.combined_gain:.3f})"
        return (
            f"with the braid's wind free within {100 * WIND_TOLERANCE:.0f} % of the declared {self.declared:g} "
            f"revolutions (calibrated {self.wind:.4g}) it is no longer the cause ({why}): the data do not tell it "
            "from a braid wound otherwise than declared"
        )

    def to_json(self) -> dict:
        j = self.mine
        return {
            "parameter": WIND,
            "declared": self.declared,
            "tolerance": WIND_TOLERANCE,
            "calibrated": self.wind,  # by the baseline alone
            "calibrated_with_cause": j.fit.baseline_params.get(WIND) if j is not None else None,
            "cause_gain_there": j.score.combined_gain if j is not None else None,
            "best_there": self.best.fit.name if self.best is not None else None,
            "margin": self.margin(),
            "survives": self.survives,
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


def check_wind(
    problem: Problem, named: Judgement, judged: list[Judgement], factories: dict, seed: int, pool
) -> BuildCheck | None:
    """The named cause (a single effect or a pair, labelled as in `factories`) and the RIVALS
    significant candidates that follow it in `judged` refitted with the braid's wind free and
    judged by decide.py's rules; None where the experiment declares the wind unknown already.
    `pool` runs the refits (a concurrent.futures executor)."""
    if winds_declared(problem.experiment):
        return None
    windy = replace(problem, predictor=Predictor(problem.experiment, problem.channels, wind=True))
    baseline = fit_baseline(windy)
    attainable = attainable_gain(windy, baseline)
    labels = named.fit.name.split("+")
    rivals = [j.fit.name for j in judged if j.significant and j.fit.name not in labels][:RIVALS]
    futures = [pool.submit(_refit, windy, baseline, label, factories[label], seed) for label in [labels[0], *rivals]]
    fits = [f.result() for f in futures]
    if len(labels) > 1 and fits[0].error is None:
        fits[0] = fit_pair(windy, fits[0], factories[labels[0]], factories[labels[1]], named.fit.name)
    there = [
        judge(windy, f, score(windy, baseline, f, np.random.default_rng(seed)), attainable)
        for f in fits
        if f.error is None
    ]
    there.sort(key=lambda j: (-j.score.combined_gain, j.score.delta_bic, j.fit.name))
    mine = next((j for j in there if j.fit.name == named.fit.name), None)
    return BuildCheck(named.fit.name, float(problem.experiment.build.fiber_revolutions), baseline, there, mine)
