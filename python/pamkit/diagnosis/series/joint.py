"""One muscle calibrated on every test of a campaign of time series at once (a campaign's
build is one muscle's: its parameters are shared and calibrated jointly).

Shared: the `[calibrate]` unknowns and the model's friction and bladder scales — one braid, one
bladder. Each test's own: its inflation pressure within the transducer's tolerance (a nuisance of
how that test was filled). The residual is every test's fitted units side by side; a test's own
coordinate moves only its own rows, so the Jacobian is block-sparse: each test's block from its
own run with sensitivities (jacobian.py), built on the pool. Then each test is compared with its
calibration alone: a muscle that fits each test by itself but not all of them together is a
structural misfit the report names (a bladder that seems stiffer at one held length than at
another). And each test is held out whole: the shared values refitted without it
(leave_one_test_out) predict its held-out units.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse

from pamkit.diagnosis.coordinates import Coordinate, configure
from pamkit.diagnosis.series.calibrate import (
    Fit,
    cluster_intervals,
    least_squares_in_box,
    penalty,
    strain_at_bounds,
    unit_to_x,
    x_to_unit,
)
from pamkit.diagnosis.series.jacobian import SENSITIVITY_STEP, applies, forward_differences, sensitivity_jacobian
from pamkit.diagnosis.series.kinds import Problem
from pamkit.diagnosis.series.model import Baseline, muscle_signature
from pamkit.io.experiment import Experiment
from pamkit.io.guards import ExperimentError
from pamkit.simulation import muscle_params

# Each test's own coordinates; every other baseline coordinate is shared.
PER_TEST = ("inflation_gauge_pressure_Pa",)
# A test whose fitted units the shared muscle fits with more than this multiple of the RMSE its own
# calibration reaches disagrees with the others. The calibrations alone reach 0.75-1.5x the noise
# on pamkit's null benchmark (significance.py), so sharing a muscle that fits costs well under 2x.
DISAGREES = 2.0


@dataclass
class TestShare:
    """How the shared muscle fits one test, against that test calibrated alone."""

    test: str
    own: dict[str, float]  # the test's own coordinates, fitted with the shared muscle
    rmse_ratio: float  # noise-weighted RMSE on its fitted units, shared / alone
    alone: dict[str, float]  # the shared values as the test fitted them by itself
    # noise-weighted RMSE on its held-out units, the shared values fitted without this test
    # (leave_one_test_out) / its own fit's
    carried_ratio: float

    @property
    def disagrees(self) -> bool:
        return self.rmse_ratio > DISAGREES


@dataclass
class JointFit:
    """One model of the muscle fitted on every test: its shared values, and how each test takes it."""

    params: dict[str, float]  # the shared values
    intervals: dict[str, tuple[float, float]]  # 95 %, clustered by half cycle within each test
    coordinates: dict[str, tuple[Coordinate, float]]  # for the bound and plausibility findings
    shares: list[TestShare]
    evaluations: int
    effect: str | None = None  # the shared effect's label, when there is one
    strain: dict[str, tuple[float, float]] = field(default_factory=dict)  # calibrate.strain_at_bounds
    # the shared values the data do not determine, each with those it trades against (identify.py)
    undetermined: dict[str, list[str]] = field(default_factory=dict)


def check_one_muscle(experiments: list[Experiment]) -> None:
    """Raises ExperimentError unless the tests declare one muscle and the same unknowns."""
    first = experiments[0]
    for e in experiments[1:]:
        if muscle_signature(muscle_params(e)) != muscle_signature(muscle_params(first)):
            raise ExperimentError(
                f"{e.path}: declares another muscle than {first.path} (its [muscle], [bladder], [friction] or [gas] "
                "differ): a campaign is of one muscle; diagnose each muscle's tests as their own campaign"
            )
        if e.calibrate != first.calibrate:
            raise ExperimentError(
                f"{e.path}: [calibrate] {dict(e.calibrate)} differs from {dict(first.calibrate)} in {first.path}: "
                "a campaign's tests share their unknowns (declare them once, in the campaign TOML)"
            )


def shared_space(problems: list[Problem]) -> list[Coordinate]:
    """The coordinates the campaign's tests share."""
    check_one_muscle([p.experiment for p in problems])
    return [c for c in Baseline.coordinates(problems[0].experiment) if c.name not in PER_TEST]


def calibrate_jointly(
    problems: list[Problem], alone: list[Fit], names: list[str], threads: int = 2, effect=None
) -> JointFit:
    """The shared muscle (and, with `effect` = (label, factory), the shared effect's parameters)
    and each test's own coordinates, fitted on every test's fitted units. `alone` holds each test's
    own fit of the same model (its calibrated baseline, or its fit of the effect), to start from
    and compare with."""
    label, make_effect = effect if effect is not None else (None, None)
    base_shared = shared_space(problems)
    # the effect's coordinates every test searches (a test's zero run holds its offsets: Problem.search_space)
    searched = [p.search_space(make_effect()) for p in problems] if make_effect is not None else [[]]
    effect_coordinates = [c for c in searched[0] if all(any(s.name == c.name for s in space) for space in searched)]
    shared = base_shared + effect_coordinates
    own = [[c for c in p.predictor.baseline.space if c.name in PER_TEST] for p in problems]
    offsets = np.cumsum([len(shared)] + [len(o) for o in own])
    sizes = [int(p.fit_mask.sum()) * len(p.channels) for p in problems]
    rows = np.concatenate([[0], np.cumsum(sizes)])
    evaluations = 0

    def model(problem: Problem, u: np.ndarray, k: int) -> tuple[np.ndarray, list]:
        x = unit_to_x(shared, u[: len(shared)])
        values = {c.name: c.value(v) for c, v in zip(base_shared, x)}
        values |= {c.name: c.value(v) for c, v in zip(own[k], unit_to_x(own[k], u[offsets[k] : offsets[k + 1]]))}
        effects = [configure(make_effect(), effect_coordinates, x[len(base_shared) :])] if make_effect else []
        return np.array([c.of(values[c.name]) for c in problem.predictor.baseline.space]), effects

    bad = [
        penalty(p, float(np.sqrt(sum(a.training_chi2.values()) / max(p.fit_mask.sum(), 1))))
        for p, a in zip(problems, alone)
    ]

    def chi(k: int, u: np.ndarray) -> np.ndarray:
        problem = problems[k]
        try:
            return problem.chi(problem.predictor.predict(*model(problem, u, k)), problem.fit_mask)
        except (ValueError, RuntimeError):
            return bad[k]

    with ThreadPoolExecutor(max_workers=threads) as pool:

        def residual(u):
            nonlocal evaluations
            evaluations += 1
            return np.concatenate(list(pool.map(lambda k: chi(k, u), range(len(problems)))))

        # Test k's residual moves with the shared coordinates and its own only.
        columns = [np.r_[0 : len(shared), offsets[k] : offsets[k + 1]] for k in range(len(problems))]

        def block(k: int, u: np.ndarray) -> np.ndarray:
            def moved(v):
                out = u.copy()
                out[columns[k]] = v
                return out

            if not applies(problems[k]):  # a supplied test: no ODE, the sensitivities' small step
                return forward_differences(lambda v: chi(k, moved(v)), u[columns[k]], SENSITIVITY_STEP)
            try:
                return sensitivity_jacobian(problems[k], lambda v: model(problems[k], moved(v), k), u[columns[k]])
            except (ValueError, RuntimeError):
                return forward_differences(lambda v: chi(k, moved(v)), u[columns[k]])

        def jac(u):
            nonlocal evaluations
            evaluations += 1
            blocks = list(pool.map(lambda k: block(k, u), range(len(problems))))
            return scipy.sparse.vstack(
                [
                    scipy.sparse.csr_matrix(
                        (b.ravel(), np.tile(columns[k], b.shape[0]), np.arange(0, b.size + 1, b.shape[1])),
                        shape=(b.shape[0], offsets[-1]),
                    )
                    for k, b in enumerate(blocks)
                ],
                format="csr",
            )

        # Each shared coordinate starts at the median of the tests' own fits, each test's own at its own.
        fitted = [{**a.baseline_params, **{k: v for k, v in a.params.items() if not isinstance(v, str)}} for a in alone]
        median = np.array([np.median([c.of(f[c.name]) for f in fitted]) for c in shared])
        u0 = np.concatenate(
            [np.clip(x_to_unit(shared, median), 0, 1)]
            + [np.clip(x_to_unit(o, np.array([c.of(f[c.name]) for c in o])), 0, 1) for o, f in zip(own, fitted)]
        )
        result = least_squares_in_box(residual, u0, 20 * (len(shared) + 1), jac=jac, tr_solver="lsmr")
    u = result.x
    clusters = np.concatenate(
        [np.tile(p.half_cycle[p.fit_mask], len(p.channels)) + 1_000_000 * k for k, p in enumerate(problems)]
    )
    jacobian = result.jac.toarray() if hasattr(result.jac, "toarray") else result.jac
    every = shared + [c for o in own for c in o]  # the shared coordinates come first
    bands, undetermined = cluster_intervals(every, u, jacobian, result.fun, clusters)
    intervals = {c.name: band for c, band in zip(shared, bands)}
    x = unit_to_x(shared, u[: len(shared)])
    carried = leave_one_test_out(jacobian, result.fun, rows, u, len(shared))
    shares = []
    for k, a in enumerate(alone):
        problem = problems[k]
        held = np.sqrt(
            np.mean(problem.chi(problem.predictor.predict(*model(problem, carried[k], k)), problem.held_mask) ** 2)
        )
        own_held = np.sqrt(np.mean(problem.chi(a.predicted, problem.held_mask) ** 2))
        misfit = result.fun[rows[k] : rows[k + 1]]
        alone_rms = np.sqrt(sum(a.training_chi2.values()) / max(sizes[k], 1))
        mine = unit_to_x(own[k], u[offsets[k] : offsets[k + 1]])
        shares.append(
            TestShare(
                names[k],
                {c.name: float(c.value(v)) for c, v in zip(own[k], mine)},
                float(np.sqrt(np.mean(misfit**2)) / alone_rms) if alone_rms > 0 else float("inf"),
                {c.name: fitted[k][c.name] for c in shared},
                float(held / own_held) if own_held > 0 else float("inf"),
            )
        )
    return JointFit(
        {c.name: float(c.value(v)) for c, v in zip(shared, x)},
        intervals,
        {c.name: (c, float(v)) for c, v in zip(shared, x)},
        shares,
        evaluations,
        label,
        {name: v for name, v in strain_at_bounds(every, u, jacobian, result.fun).items() if name not in PER_TEST},
        {name: v for name, v in undetermined.items() if name in intervals},
    )


def leave_one_test_out(
    jacobian: np.ndarray, residual: np.ndarray, rows: np.ndarray, u: np.ndarray, n_shared: int
) -> list[np.ndarray]:
    """Each test's coordinates with the shared ones refitted without that test's rows: one
    Gauss-Newton step from the joint solution (the approximate leave-one-out of least squares),
    u₋ₖ = u + (JᵀJ − JₖᵀJₖ)⁺ Jₖᵀ rₖ, in the unit box; the test's own coordinates keep their joint
    values (they are fitted on its fitted units, which the held-out units are not)."""
    out = []
    normal = jacobian.T @ jacobian
    for k in range(len(rows) - 1):
        block = jacobian[rows[k] : rows[k + 1]]
        step = np.linalg.pinv(normal - block.T @ block) @ (block.T @ residual[rows[k] : rows[k + 1]])
        moved = u.copy()
        moved[:n_shared] = np.clip(u[:n_shared] + step[:n_shared], 0.0, 1.0)
        out.append(moved)
    return out
