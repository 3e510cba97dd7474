"""The calibrated baseline: the model's own uncertain parameters (inflation pressure within the
transducer's tolerance, a friction scale, a bladder scale) fitted on the fitted units, and the
least-squares machinery every fit shares."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares

from pamkit._core import Effect
from pamkit.diagnose.kinds import Problem
from pamkit.diagnose.model import Coordinate

# Finite-difference step in the unit box of each coordinate: large enough that the
# integrator's adaptive steps (relative error ~1e-7) do not swamp the slopes.
DIFF_STEP = 1e-3


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


def unit_to_x(space: list[Coordinate], u: np.ndarray) -> np.ndarray:
    return np.array([c.lower + ui * (c.upper - c.lower) for c, ui in zip(space, u)])


def x_to_unit(space: list[Coordinate], x: np.ndarray) -> np.ndarray:
    return np.array([(xi - c.lower) / (c.upper - c.lower) for c, xi in zip(space, x)])


def start_unit(space: list[Coordinate]) -> np.ndarray:
    return np.clip(x_to_unit(space, np.array([c.start for c in space])), 0.0, 1.0)


def solve(residual, u0: np.ndarray, max_evaluations: int) -> np.ndarray:
    """SciPy's bounded trust-region least squares in the unit box."""
    result = least_squares(
        residual, u0, bounds=(0.0, 1.0), method="trf", diff_step=DIFF_STEP, x_scale=1.0, max_nfev=max_evaluations
    )
    return result.x


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

    u = solve(residual, start_unit(space), 20 * (len(space) + 1))
    x = unit_to_x(space, u)
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
    )
