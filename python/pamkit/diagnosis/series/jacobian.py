"""The Jacobian of a fit's residual from one run with CVODES forward sensitivities.

A fit moves coordinates in its unit box; each coordinate maps to the model's parameters (a
pressure, a scale, a build field, an effect's parameter) and to its instruments. Differencing two
adaptively stepped runs mixes the slope with the integrator's own error, so the finite
differences a fit used before had to step a thousandth of the box (DIFF_STEP). Here one
run integrates the sensitivities of the state to every coordinate that moves the model beside the
state (Simulator.run_sensitivities), on the run's own steps; the instruments, a cheap post-process
of the run's channels, are differenced at the first-order moved channels. A coordinate that only
moves an instrument needs no sensitivity at all. A coordinate that moves the muscle off the
crosshead's motion (a fixture's slack) gives its moved model that moved motion: the run follows
the nominal motion, and each sensitivity its own. Where every effect reads each sample alone (no
lag, no skew), the run evaluates the moved models only at the fitted units' samples, where the
Jacobian reads them (about half of a record's; the sensitivity runs take 10-30 % less).

A supplied-pressure test has no ODE: its model is evaluated sample by sample, each braid closure
solved to ~1e-14, so it is differenced with the sensitivities' small step (static tables do the
same in tables/fit.py). Runs are differenced at DIFF_STEP only where a moved model leaves its
range (the fit then goes on as it did before sensitivities).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from pamkit._core import Effect, ElongationTrajectory, GasMode, Measurement
from pamkit.diagnosis.series.kinds import Problem
from pamkit.diagnosis.series.model import muscle_signature

# Finite-difference step in the unit box of each coordinate, where a fit differences runs: large
# enough that the integrator's adaptive steps (relative error ~1e-7) do not swamp the slopes.
DIFF_STEP = 1e-3
# Step in the unit box of the sensitivities' difference quotients (of smooth model functions
# solved to ~1e-14, not of runs): derivatives to ~1e-6 relative (tests/python/diagnose/test_jacobian.py).
SENSITIVITY_STEP = 1e-6

# A fit's point: the baseline coordinates and freshly made, configured effects at unit coordinates u.
Point = Callable[[np.ndarray], tuple[np.ndarray, list[Effect]]]


def applies(problem: Problem) -> bool:
    """Whether a sensitivity run gives this fit's Jacobian: a sealed test (an ODE)."""
    return problem.predictor.mode == GasMode.sealed


def muscle_motion(problem: Problem, effects: list[Effect]) -> ElongationTrajectory:
    """The muscle's elongation along the crosshead's motion, moved by every effect in order (the
    pipeline's apply_to_elongation; the crosshead's own where no effect acts on the motion)."""
    predictor = problem.predictor
    if not predictor.moves_muscle(effects):
        return predictor.trajectory
    trajectory = predictor.played_trajectory
    time_s = np.asarray(trajectory.time_s)
    elongation = np.asarray(trajectory.elongation_m)
    for effect in effects:
        elongation = np.asarray(effect.apply_to_elongation(time_s, elongation))  # a Python effect may give a list
    return ElongationTrajectory(time_s, elongation)


def _key(model) -> tuple:
    initial = model.initial_state
    return (
        muscle_signature(model.params),
        model.params.gas.ambient_temperature_K,
        initial.length_m,
        initial.gauge_pressure_Pa,
    )


def _channels(run, crosshead_m: np.ndarray, derivative=None, step: float = 0.0) -> Measurement:
    """The channels a sealed test's instruments read of `run` (simulate_measurement's, the
    elongation the crosshead's), moved by step x `derivative` when given."""

    def column(name):
        values = np.asarray(getattr(run, name))
        return values + step * np.asarray(getattr(derivative, name)) if derivative is not None else values

    m = Measurement()
    m.time_s = np.asarray(run.time_s)
    m.elongation_m = crosshead_m
    m.force_N = column("force_N")
    m.gauge_pressure_Pa = column("gauge_pressure_Pa")
    m.temperature_K = column("temperature_K")
    return m


def _read(problem: Problem, m: Measurement, effects: list[Effect], mask: np.ndarray) -> np.ndarray:
    for effect in effects:
        m = effect.apply_to_measurement(m)
    return problem.chi(problem.predictor.select(m), mask)


def rows_read(problem: Problem, effects: list[list[Effect]]) -> np.ndarray:
    """The run's samples the fitted units read, where every effect (`effects`: the nominal
    point's and each moved point's) reads each sample alone; else none, which asks for every
    sample."""
    if not all(x.reads_samples_alone() for e in effects for x in e):
        return np.empty(0, dtype=np.uint64)
    return problem.predictor.run_rows(problem.fit_mask, effects[0])


def sensitivity_jacobian(problem: Problem, point: Point, u: np.ndarray) -> np.ndarray:
    """d chi / du at u on the fitted units, from one run with the sensitivities of every
    coordinate that moves the model. Each step is SENSITIVITY_STEP into the box. Raises
    ValueError or RuntimeError where a moved model leaves its range."""
    predictor = problem.predictor
    mask = problem.fit_mask
    steps = np.where(u + SENSITIVITY_STEP <= 1.0, SENSITIVITY_STEP, -SENSITIVITY_STEP)
    base_x, effects = point(u)
    nominal = predictor.sealed_model(base_x, effects)
    motion = muscle_motion(problem, effects)
    moved_points = [point(u + step * np.eye(len(u))[j]) for j, step in enumerate(steps)]
    moved_models = [predictor.sealed_model(x, e) for x, e in moved_points]
    moved_motions = [muscle_motion(problem, e) for _, e in moved_points]
    nominal_key = _key(nominal)
    nominal_elongation = np.asarray(motion.elongation_m)
    moves_motion = [m is not motion and not np.array_equal(m.elongation_m, nominal_elongation) for m in moved_motions]
    moves_model = [_key(m) != nominal_key or on_motion for m, on_motion in zip(moved_models, moves_motion)]
    # A table of the braid's shapes along the crosshead's motion serves only runs that follow it.
    shapes = predictor.shape_table(nominal.params, nominal.initial_state) if motion is predictor.trajectory else None
    result = predictor.simulator.run_sensitivities(
        nominal,
        [m for m, moves in zip(moved_models, moves_model) if moves],
        [float(h) for h, moves in zip(steps, moves_model) if moves],
        motion,
        shapes,
        [m for m, moves in zip(moved_motions, moves_model) if moves] if any(moves_motion) else [],
        rows_read(problem, [effects] + [e for _, e in moved_points]),
    )
    crosshead = np.asarray(predictor.trajectory.elongation_m)
    run, derivatives = result.run, result.derivatives
    if predictor.moves_muscle(effects):
        run, derivatives = predictor.played_measurement(run), [predictor.played_measurement(d) for d in derivatives]
    chi = _read(problem, _channels(run, crosshead), effects, mask)
    derivatives = iter(derivatives)
    jacobian = np.empty((chi.size, len(u)))
    for j, ((_, moved_effects), h, moves) in enumerate(zip(moved_points, steps, moves_model)):
        channels = _channels(run, crosshead, next(derivatives), h) if moves else _channels(run, crosshead)
        jacobian[:, j] = (_read(problem, channels, moved_effects, mask) - chi) / h
    return jacobian


def forward_differences(
    residual: Callable[[np.ndarray], np.ndarray], u: np.ndarray, step: float = DIFF_STEP
) -> np.ndarray:
    """SciPy's 2-point scheme stepping into the box: at DIFF_STEP, the fits' former Jacobian,
    where a moved model leaves its range (the fit goes on as it did without sensitivities); at
    SENSITIVITY_STEP for a model without an ODE."""
    r0 = residual(u)
    steps = np.where(u + step <= 1.0, step, -step)
    return np.column_stack([(residual(u + h * np.eye(len(u))[j]) - r0) / h for j, h in enumerate(steps)])


def jacobian_for(
    problem: Problem,
    point: Point,
    residual: Callable[[np.ndarray], np.ndarray],
    on_run: Callable[[], None] = lambda: None,
):
    """The `jac` a fit hands least_squares: sensitivities for a sealed test (`applies`), small-step
    differences without an ODE (a supplied test), differences of runs at DIFF_STEP where a moved
    model leaves its range. `on_run` is called for each run with sensitivities (a fit counts its
    model runs)."""
    if not applies(problem):
        return lambda u: forward_differences(residual, u, SENSITIVITY_STEP)

    def jac(u: np.ndarray) -> np.ndarray:
        try:
            on_run()
            return sensitivity_jacobian(problem, point, u)
        except (ValueError, RuntimeError):
            return forward_differences(residual, u)

    return jac
