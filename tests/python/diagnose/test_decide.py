"""The decision rules of python/pamkit/diagnosis/decide.py on scores made by hand: what each rule
does with two candidates, without fitting anything."""

from types import SimpleNamespace

import numpy as np

from pamkit.diagnosis.calibrate import Fit
from pamkit.diagnosis.decide import Judgement, Score, decide

SAMPLES = 1000
rng = np.random.default_rng(7)
SHARED = rng.normal(0.0, 0.02, SAMPLES)  # what the bootstrap draws do to every candidate alike


def problem():
    """One channel whose held-out samples every fit below predicts exactly (nothing left)."""
    measured = np.zeros(20)
    return SimpleNamespace(
        channels=["force_N"], measured={"force_N": measured}, sigma={"force_N": 1.0}, held_mask=np.ones(20, bool)
    )


def candidate(name: str, gain: float, samples: np.ndarray, objections=()) -> Judgement:
    effect = SimpleNamespace(name=lambda: name)
    fit = Fit(name, [effect], np.zeros(0), {}, {"force_N": np.zeros(20)}, {"force_N": 0.0}, 1)
    score = Score(
        rmse={"force_N": 1.0},
        gain={"force_N": gain},
        gain_ci95={"force_N": [gain - 0.04, gain + 0.04]},
        combined_gain=gain,
        combined_ci95=[float(np.percentile(samples, 2.5)), float(np.percentile(samples, 97.5))],
        delta_bic=-100.0,
        credited_gain=gain,
        credited_ci95=[gain - 0.04, gain + 0.04],
        combined_samples=samples,
    )
    return Judgement(fit, score, True, [], list(objections))


def test_two_mechanisms_the_data_cannot_tell_apart_are_not_a_cause():
    # Gains 0.30 and 0.29 on the same draws, each draw's difference spread 0.03: the paired
    # interval of the difference holds zero.
    best = candidate("dead_volume", 0.30, 0.30 + SHARED + rng.normal(0, 0.02, SAMPLES))
    rival = candidate("fiber_compliance", 0.29, 0.29 + SHARED + rng.normal(0, 0.02, SAMPLES))
    baseline = Fit("none", [], np.zeros(0), {}, {"force_N": np.full(20, 5.0)}, {"force_N": 0.0}, 0)
    decision = decide(problem(), baseline, [best, rival])
    assert decision.cause == "unexplained"
    assert decision.rejected is best and "fiber_compliance explains the held-out units as well" in best.reasons()[0]
    assert decision.margins["over_rival"] <= 0.0


def test_a_cause_that_beats_its_rival_on_the_same_draws_is_named():
    # The same spread, 0.10 apart: the difference's interval lies above zero.
    best = candidate("dead_volume", 0.40, 0.40 + SHARED + rng.normal(0, 0.02, SAMPLES))
    rival = candidate("fiber_compliance", 0.30, 0.30 + SHARED + rng.normal(0, 0.02, SAMPLES))
    decision = decide(problem(), None, [best, rival])
    assert decision.cause == "dead_volume" and decision.margins["over_rival"] > 0.0


def test_a_rival_that_is_not_credible_does_not_block_a_cause():
    best = candidate("dead_volume", 0.30, 0.30 + SHARED + rng.normal(0, 0.02, SAMPLES))
    rival = candidate("sensor_offset", 0.29, 0.29 + SHARED, objections=["gain = 0.5 ended at its search bound"])
    decision = decide(problem(), None, [best, rival])
    assert decision.cause == "dead_volume" and "over_rival" not in decision.margins
