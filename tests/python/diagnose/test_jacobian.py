"""A fit's Jacobian from one run with CVODES forward sensitivities (python/pamkit/diagnosis/series/jacobian.py),
checked against central differences of tightly integrated runs, as Crocoddyl checks its
analytic derivatives against numdiff; and where it does not apply, SciPy's differences remain."""

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from pamkit._core import GasMode, SimulatorConfig
from pamkit.diagnosis.coordinates import configure, effect_space
from pamkit.diagnosis.series import jacobian
from pamkit.diagnosis.series.calibrate import fit_baseline, start_unit, unit_to_x
from pamkit.diagnosis.series.kinds import build_problem
from pamkit.diagnosis.series.model import Predictor
from pamkit.effects import catalog
from pamkit.io.experiment import load_experiment

EXAMPLE = Path(__file__).resolve().parents[3] / "data" / "experiments" / "example" / "experiment.toml"
TIGHT = SimulatorConfig(relative_tolerance=1e-10, absolute_tolerance_K=1e-10)


def tight_problem():
    problem = build_problem(load_experiment(EXAMPLE))
    return dataclasses.replace(problem, predictor=Predictor(problem.experiment, problem.channels, TIGHT))


def point_with(problem, names):
    """The fit's point over the baseline and the effects `names`, fresh effects each call."""
    space = problem.predictor.baseline.space
    spaces = [effect_space(catalog().make(n)) for n in names]
    sizes = np.cumsum([len(space)] + [len(s) for s in spaces])

    def point(u):
        effects = [
            configure(catalog().make(n), s, unit_to_x(s, u[a:b]))
            for n, s, a, b in zip(names, spaces, sizes[:-1], sizes[1:])
        ]
        return unit_to_x(space, u[: len(space)]), effects

    start = np.concatenate([start_unit(space)] + [start_unit(s) for s in spaces])
    return point, start


@pytest.mark.parametrize(
    "names",
    [
        # The baseline (inflation pressure, which moves the free length, friction and bladder
        # scales), a physical effect and an instrument.
        ["heat_transfer", "sensor_lag"],
        # Effects that read each sample alone: the run's derivatives at the fitted rows only.
        ["dead_volume", "load_cell"],
        # An effect that moves the muscle off the crosshead's motion: its sensitivity follows
        # its own moved motion.
        ["fixture_slack"],
    ],
)
def test_the_sensitivity_jacobian_is_central_differences_of_tight_runs(names):
    problem = tight_problem()
    point, u = point_with(problem, names)
    u = np.clip(u + 0.1, 0.0, 0.9)  # off the starts

    def residual(v):
        x, effects = point(v)
        return problem.chi(problem.predictor.predict(x, effects), problem.fit_mask)

    exact = jacobian.sensitivity_jacobian(problem, point, u)
    # Central differences at 1e-4 of the box: truncation ~1e-8 of a slope, the runs' own error
    # (rtol 1e-10) ~1e-6 of it.
    h = 1e-4
    central = np.column_stack([(residual(u + h * e) - residual(u - h * e)) / (2 * h) for e in np.eye(len(u))])
    for j in range(len(u)):
        gap = np.linalg.norm(exact[:, j] - central[:, j]) / np.linalg.norm(central[:, j])
        # Measured: at most 3.2e-5 (heat_transfer's time constant, through the integrated temperature).
        assert gap < 1e-4, f"column {j}: {gap:.2e}"


def test_the_run_reads_derivatives_at_the_fitted_rows_only_where_every_effect_reads_samples_alone():
    problem = build_problem(load_experiment(EXAMPLE))

    def rows(names):
        return jacobian.rows_read(problem, [[catalog().make(n) for n in names]])

    fitted = problem.predictor.motion.sample_rows[problem.fit_mask]
    assert 0 < fitted.size < problem.predictor.motion.sample_rows.size
    np.testing.assert_array_equal(rows(["dead_volume", "load_cell", "sensor_offset", "thermometer"]), fitted)
    assert np.all(np.diff(fitted) > 0)  # as the simulator requires
    # A lag or a skew reads the neighbours of a fitted row: every sample then.
    for names in (["sensor_lag"], ["load_cell", "time_skew"]):
        assert rows(names).size == 0, names
    # A fixture's play moves the muscle along the played motion's finer knots, read at the motion's.
    played = rows(["fixture_slack", "load_cell"])
    assert played.size == fitted.size and np.all(np.diff(played) > 0) and played[-1] > fitted[-1]


def test_a_fit_with_sensitivities_reaches_the_finite_difference_fits_optimum(monkeypatch):
    problem = build_problem(load_experiment(EXAMPLE))
    exact = fit_baseline(problem)
    monkeypatch.setattr("pamkit.diagnosis.series.calibrate.jacobian_for", lambda *args: "2-point")
    differenced = fit_baseline(problem)
    for name, (low, high) in exact.intervals.items():
        # The two optima agree to a thousandth of the parameter's own 95 % interval (measured: 5e-5).
        assert abs(exact.params[name] - differenced.params[name]) < 1e-3 * (high - low), name


def test_sealed_tests_take_sensitivities_and_supplied_tests_small_steps():
    sealed = build_problem(load_experiment(EXAMPLE))
    assert jacobian.applies(sealed)
    supplied = dataclasses.replace(sealed)
    supplied.predictor = Predictor(sealed.experiment, sealed.channels)
    supplied.predictor.mode = GasMode.supplied  # its model is static: sample by sample, no ODE
    assert not jacobian.applies(supplied)
    steps = []

    def residual(u):
        steps.append(u.copy())
        return np.array([u[0] ** 2])

    jac = jacobian.jacobian_for(supplied, None, residual)
    assert jac(np.array([0.5])) == pytest.approx(1.0, abs=1e-5)  # d(u^2)/du at 0.5, step 1e-6
    assert abs(steps[1][0] - steps[0][0]) == pytest.approx(jacobian.SENSITIVITY_STEP)
