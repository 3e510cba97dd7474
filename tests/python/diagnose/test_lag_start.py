"""A channel shifted in time by more than a fraction of a cycle (candidates.lag_start): the
least-squares surface of a shift repeats with the cycles, and a baseline calibrated on the skewed
data bends towards them, so a grid on it can rank another cycle's minimum first. The shift's search
starts also where the measured and predicted rates correlate best, which does not depend on the
baseline's shape. Checked as an estimator against the skew written in, and as a decision over
seeds."""

import numpy as np
import pytest

from pamkit.diagnosis import diagnose
from pamkit.diagnosis.coordinates import effect_space
from pamkit.diagnosis.series.calibrate import fit_baseline, one_blas_thread
from pamkit.diagnosis.series.candidates import lag_start
from pamkit.diagnosis.series.kinds import build_problem
from pamkit.effects import catalog
from pamkit.io.experiment import load_experiment
from pamkit.synth.dataset import synthesize

# Skews of one to two and a half seconds: several samples at every rate pamkit synth draws, and a
# sizeable share of a stretch cycle (bench_diagnose seed 1035: 1.65 s, fitted at 4.0 s on a grid).
SKEWS_S = {1035: 1.65, 1047: 1.2, 1059: 2.4, 1071: -1.8}
PRESSURE = "gauge_pressure_Pa"


def skewed(seed, tmp_path):
    spec = f"time_skew:channel={PRESSURE},offset_s={SKEWS_S[seed]}"
    return load_experiment(synthesize(spec, seed, tmp_path).experiment)


@pytest.mark.parametrize("seed", sorted(SKEWS_S))
def test_the_rates_cross_correlation_finds_the_skew_written_in(seed, tmp_path):
    experiment = skewed(seed, tmp_path)
    with one_blas_thread():
        problem = build_problem(experiment)
        baseline = fit_baseline(problem)
    effect = catalog().parse(f"time_skew:channel={PRESSURE}")
    (start,) = lag_start(problem, baseline, effect, effect_space(effect))
    interval = float(np.median(np.diff(experiment.time_s)))
    # Within one sample: the correlation is evaluated at whole-sample lags.
    assert start == pytest.approx(SKEWS_S[seed], abs=interval)


def test_an_effect_that_is_no_shift_has_no_lag_start(tmp_path):
    experiment = skewed(1035, tmp_path)
    with one_blas_thread():
        problem = build_problem(experiment)
        baseline = fit_baseline(problem)
    for name in ("leak", "sensor_offset"):
        effect = catalog().make(name)
        assert lag_start(problem, baseline, effect, effect_space(effect)) == []


def test_large_skews_are_named_over_seeds(tmp_path):
    # Every seed: a skew of several samples with nothing else hidden is the plainest signature the
    # catalog has (held-out gains of 0.95-1.0 once fitted at the right cycle).
    named = 0
    for seed in sorted(SKEWS_S):
        report = diagnose(skewed(seed, tmp_path / str(seed)), threads=2)
        causes = [c.label for c in report.decision.causes]
        assert causes in ([], [f"time_skew:channel={PRESSURE}"]), (seed, causes)
        named += causes == [f"time_skew:channel={PRESSURE}"]
    assert named == len(SKEWS_S)
