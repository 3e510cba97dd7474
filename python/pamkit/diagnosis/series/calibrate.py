"""The calibrated baseline: the model's own uncertain parameters (inflation pressure within the
transducer's tolerance, a friction scale, a bladder scale) fitted on the fitted units, and the
least-squares machinery every fit shares."""

from __future__ import annotations

import functools
import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import OptimizeResult, least_squares
from threadpoolctl import ThreadpoolController

from pamkit._core import Effect
from pamkit.diagnosis.coordinates import Coordinate
from pamkit.diagnosis.identify import Z95, identify
from pamkit.diagnosis.series.jacobian import DIFF_STEP, jacobian_for
from pamkit.diagnosis.series.kinds import Problem


@dataclass
class Fit:
    """One fitted model: which effects, their parameters, and its predictions."""

    name: str
    effects: list[Effect]
    baseline_x: np.ndarray
    params: dict[str, float]
    predicted: dict[str, np.ndarray]
    training_chi2: dict[str, float]  # per channel, on the fitted units
    parameter_count: int
    evaluations: int = 0
    error: str | None = None
    baseline_params: dict[str, float] = field(default_factory=dict)
    # (coordinate, fitted coordinate value) of every fitted parameter, effect parameters keyed
    # as in `params`, for the bound and plausibility checks
    coordinates: dict[str, tuple[Coordinate, float]] = field(default_factory=dict)
    # 95 % intervals of the fitted baseline values (cluster_intervals), where computed
    intervals: dict[str, tuple[float, float]] = field(default_factory=dict)
    # the fitted values the data do not determine, each with those it trades against (identify.py)
    undetermined: dict[str, list[str]] = field(default_factory=dict)
    # per coordinate at a bound: (value the fit would reach without the bound, fitted-RMSE drop
    # there), where computed (strain_at_bounds)
    strain: dict[str, tuple[float, float]] = field(default_factory=dict)
    # a candidate left after one Gauss-Newton step (candidates.SCREEN_DROP): the fitted
    # chi-square's drop that step predicted, as a share of the calibrated baseline's; else None
    screened: float | None = None
    # d chi / du on the fitted units at the solution, in the search box's unit coordinates (the
    # calibrated baseline's: a candidate's screening step starts from it)
    jacobian: np.ndarray | None = field(default=None, repr=False)


def thread_pool(threads: int | None) -> ThreadPoolExecutor:
    """The fits' pool: `threads` at a time, by default one per core (their runs release the GIL)."""
    return ThreadPoolExecutor(max_workers=threads or os.cpu_count() or 1)


def one_blas_thread():
    """A context in which NumPy's and SciPy's BLAS run on one thread. A diagnosis's residuals are
    long (10⁴ rows; a campaign's joint fit holds every test's units side by side, 10⁵): long
    enough for OpenBLAS to split each norm and product over threads of its own, on top of the
    diagnosis's `threads` simulating, and a sum split over threads may round otherwise on a
    machine with another core count. On this project's 2 shared cores that made a norm of 55 000 values take
    5 ms instead of 20 µs, the campaign's joint part 1.2-2x slower and the whole campaign use a
    fifth more CPU (bench/README.md, "A campaign of the thesis's tests"): the parallelism is the
    simulations'. The limit is the process's while the context lasts (threadpoolctl)."""
    return _blas_libraries().limit(limits=1, user_api="blas")


@functools.cache
def _blas_libraries() -> ThreadpoolController:
    """The process's BLAS libraries, found once: threadpoolctl reads the loaded libraries, 3-30 ms
    a search (measured), every diagnosis otherwise. NumPy's and SciPy's are loaded by then."""
    return ThreadpoolController()


def unit_to_x(space: list[Coordinate], u: np.ndarray) -> np.ndarray:
    return np.array([c.lower + ui * (c.upper - c.lower) for c, ui in zip(space, u)])


def x_to_unit(space: list[Coordinate], x: np.ndarray) -> np.ndarray:
    return np.array([(xi - c.lower) / (c.upper - c.lower) for c, xi in zip(space, x)])


def start_unit(space: list[Coordinate]) -> np.ndarray:
    return np.clip(x_to_unit(space, np.array([c.start for c in space])), 0.0, 1.0)


def least_squares_in_box(residual, u0: np.ndarray, max_evaluations: int, jac="2-point", **options) -> OptimizeResult:
    """SciPy's bounded trust-region least squares in the unit box; `jac` a callable (jacobian.py)
    or SciPy's 2-point differences at DIFF_STEP."""
    return least_squares(
        residual,
        u0,
        jac=jac,
        bounds=(0.0, 1.0),
        method="trf",
        diff_step=DIFF_STEP,
        x_scale=1.0,
        max_nfev=max_evaluations,
        **options,
    )


def cluster_intervals(
    space: list[Coordinate], u: np.ndarray, jacobian: np.ndarray, residual: np.ndarray, clusters: np.ndarray
) -> tuple[list[tuple[float, float]], dict[str, list[str]]]:
    """95 % intervals of fitted values from the least-squares Jacobian at the solution, with the
    covariance clustered by unit (the sandwich (JᵀJ)⁻¹ (Σ_g J_gᵀ r_g r_gᵀ J_g) (JᵀJ)⁻¹ · G/(G−1)):
    residuals correlated within a half cycle do not shrink the interval as if independent.
    `clusters` gives each residual's unit. One interval per coordinate of `space`, in its order,
    and the coordinates the data do not determine (identify.py), each with those it trades
    against: their interval is their whole search interval, never a zero width."""
    labels = np.unique(clusters)
    scores = np.array([jacobian[clusters == g].T @ residual[clusters == g] for g in labels])
    meat = scores.T @ scores * len(labels) / max(len(labels) - 1, 1)
    found = identify(jacobian, meat)
    sd_u = np.sqrt(np.clip(np.diag(found.covariance), 0.0, None))
    out = []
    for index, (c, ui, sd) in enumerate(zip(space, u, sd_u)):
        # Within the search interval: a scale cannot go below zero because its interval is wide.
        ends = (
            [c.value(c.lower), c.value(c.upper)]
            if index in found.undetermined
            else [
                c.value(c.lower + np.clip(ui + sign * Z95 * sd, 0.0, 1.0) * (c.upper - c.lower)) for sign in (-1.0, 1.0)
            ]
        )
        out.append((float(min(ends)), float(max(ends))))
    return out, found.trades_against([c.name for c in space])


def strain_at_bounds(
    space: list[Coordinate], u: np.ndarray, jacobian: np.ndarray, residual: np.ndarray
) -> dict[str, tuple[float, float]]:
    """How much a fit strains against the bounds it ended at: one Gauss-Newton step from the
    solution with the bounds lifted, δ = −(JᵀJ)⁺ Jᵀ r, gives where each coordinate at a bound
    would go and, to first order, the fitted RMSE there, 1 − |r + J δ| / |r| lower. Only
    coordinates the step pushes further past their bound are reported."""
    step = -np.linalg.pinv(jacobian.T @ jacobian) @ (jacobian.T @ residual)
    norm = float(np.linalg.norm(residual))
    drop = 1.0 - float(np.linalg.norm(residual + jacobian @ step)) / norm if norm > 0 else 0.0
    out = {}
    for c, ui, di in zip(space, u, step):
        side = c.at_bound(c.lower + ui * (c.upper - c.lower))
        if (side == "lower" and di < 0) or (side == "upper" and di > 0):
            out[c.name] = (float(c.value(c.lower + (ui + di) * (c.upper - c.lower))), drop)
    return out


def penalty(problem: Problem, scale: float) -> np.ndarray:
    """The residual of parameters that drive the model out of its range (a braid stretched
    past its fibers' length, a root not bracketed): a bad fit, not a failed diagnosis."""
    return np.full(int(problem.fit_mask.sum()) * len(problem.channels), 10.0 * (1.0 + scale))


def baseline_coordinates(problem: Problem, x: np.ndarray) -> dict[str, tuple[Coordinate, float]]:
    return {c.name: (c, float(v)) for c, v in zip(problem.predictor.baseline.space, x)}


def fit_baseline(problem: Problem) -> Fit:
    """The baseline calibrated on the fitted units."""
    space = problem.predictor.baseline.space
    evaluations = 0
    start_chi = problem.chi(problem.predictor.predict(unit_to_x(space, start_unit(space)), []), problem.fit_mask)
    bad_fit = penalty(problem, float(np.sqrt(np.mean(start_chi**2))))

    def residual(u):
        nonlocal evaluations
        evaluations += 1
        try:
            return problem.chi(problem.predictor.predict(unit_to_x(space, u), []), problem.fit_mask)
        except (ValueError, RuntimeError):
            return bad_fit

    def counted():
        nonlocal evaluations
        evaluations += 1

    jac = jacobian_for(problem, lambda u: (unit_to_x(space, u), []), residual, counted)
    result = least_squares_in_box(residual, start_unit(space), 20 * (len(space) + 1), jac=jac)
    u, x = result.x, unit_to_x(space, result.x)
    bands, undetermined = cluster_intervals(space, u, result.jac, result.fun, problem.residual_units())
    intervals = {c.name: band for c, band in zip(space, bands)}
    strain = strain_at_bounds(space, u, result.jac, result.fun)
    predicted = problem.predictor.predict(x, [])
    values = problem.predictor.baseline.values(x)
    return Fit(
        "none",
        [],
        x,
        values,
        predicted,
        problem.chi2_by_channel(predicted),
        len(space),
        evaluations,
        baseline_params=values,
        coordinates=baseline_coordinates(problem, x),
        intervals=intervals,
        undetermined=undetermined,
        strain=strain,
        jacobian=result.jac,
    )
