"""How python/pamkit/diagnosis/series/causes.py picks what to fit beside a first cause, on a model made
by hand: which candidate's step beside the first takes what the first leaves."""

from types import SimpleNamespace

import numpy as np

from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.causes import _step_beside
from pamkit.effects import catalog

ROWS = 50
PRESSURE = "gauge_pressure_Pa"
TIME = np.linspace(0.0, 1.0, ROWS)


def shapes(effects):
    """What a second effect does to the pressure beside a skew: a leak's drift over the test, an
    offset's constant, and a lag that the model cannot run."""
    second = effects[1].name()
    if second == "sensor_lag":
        raise RuntimeError("the run failed")
    return {PRESSURE: {"leak": -TIME, "sensor_offset": np.ones(ROWS)}[second]}


def candidate(name):
    return SimpleNamespace(fit=SimpleNamespace(name=name))


def test_the_partner_whose_step_beside_the_first_takes_its_remainder():
    # A skew fitted first leaves the pressure drifting down over the test (what a slow leak does);
    # fitted alone the leak gained nothing (the skew's misfit dwarfed its drift). Of a leak's step,
    # an offset's and a run that fails, the leak's beside the skew takes the drift.
    problem = SimpleNamespace(
        channels=[PRESSURE],
        fit_mask=np.ones(ROWS, bool),
        sigma={PRESSURE: 1.0},
        measured={PRESSURE: -0.3 * TIME},
        predictor=SimpleNamespace(predict=lambda base_x, effects: shapes(effects)),
    )
    skew = Fit("time_skew", [], np.zeros(0), {"offset_s": 0.5}, {PRESSURE: np.zeros(ROWS)}, {PRESSURE: 0.0}, 1)
    names = ("time_skew", "leak", "sensor_offset", "sensor_lag")
    factories = {name: (lambda name=name: catalog().make(name)) for name in names}
    left = problem.measured[PRESSURE] - skew.predicted[PRESSURE]
    others = [candidate("sensor_offset"), candidate("sensor_lag"), candidate("leak")]
    assert _step_beside(problem, skew, left, others, factories) is others[2]
    # Without the leak the offset takes a share of the drift (its mean), and is the one.
    assert _step_beside(problem, skew, left, others[:2], factories) is others[0]
    # A run the model cannot make is no direction: with nothing else to step, no partner.
    assert _step_beside(problem, skew, left, others[1:2], factories) is None
