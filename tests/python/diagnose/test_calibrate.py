"""The least-squares helpers of python/pamkit/diagnosis/series/calibrate.py against closed forms."""

import numpy as np
import pytest

from pamkit.diagnosis.coordinates import Coordinate
from pamkit.diagnosis.series.calibrate import cluster_intervals, strain_at_bounds


def test_cluster_intervals_of_a_mean_are_its_standard_error():
    # Fitting a constant to n samples, each its own cluster: the sandwich with the G/(G-1)
    # correction is s^2 / n exactly, s the sample standard deviation, so the interval is the
    # textbook mean +- 1.96 s / sqrt(n).
    rng = np.random.default_rng(3)
    y = 0.4 + 0.05 * rng.standard_normal(50)
    mean = float(y.mean())
    residual = mean - y
    jacobian = np.ones((y.size, 1))
    ((low, high),), _ = cluster_intervals(
        [Coordinate("level", 0.0, 1.0, 0.5)], np.array([mean]), jacobian, residual, np.arange(y.size)
    )
    half = 1.96 * y.std(ddof=1) / np.sqrt(y.size)
    assert (low, high) == pytest.approx((mean - half, mean + half), rel=1e-12)


def test_cluster_intervals_widen_for_residuals_correlated_within_a_cluster():
    # The same 50 residuals, each repeated four times (a half cycle of identical errors): treated
    # as independent the interval would shrink by 2; clustered, it stays the one above.
    rng = np.random.default_rng(3)
    y = np.repeat(0.4 + 0.05 * rng.standard_normal(50), 4)
    mean = float(y.mean())
    jacobian = np.ones((y.size, 1))
    space = [Coordinate("level", 0.0, 1.0, 0.5)]
    ((low, high),), _ = cluster_intervals(space, np.array([mean]), jacobian, mean - y, np.repeat(np.arange(50), 4))
    ((naive_low, naive_high),), _ = cluster_intervals(space, np.array([mean]), jacobian, mean - y, np.arange(y.size))
    assert (high - low) / (naive_high - naive_low) == pytest.approx(2.0, rel=0.02)


def test_strain_at_a_bound_is_the_unbounded_solution_of_a_linear_problem():
    # r(u) = A u - b, whose unbounded least-squares solution has u0 < 0: bounded to [0, 1], u0
    # ends at 0; one Gauss-Newton step from there is exact for a linear residual.
    a = np.array([[1.0, 0.2], [0.3, 1.0], [0.5, 0.5], [1.0, -0.4]])
    b = np.array([-0.3, 0.6, 0.1, -0.5])
    free, *_ = np.linalg.lstsq(a, b, rcond=None)
    assert free[0] < 0 < free[1] < 1
    bounded_u1 = float(a[:, 1] @ b / (a[:, 1] @ a[:, 1]))  # u0 = 0, u1 fitted alone
    u = np.array([0.0, bounded_u1])
    space = [Coordinate("u0", 0.0, 1.0, 0.5), Coordinate("u1", 0.0, 1.0, 0.5)]
    strain = strain_at_bounds(space, u, a, a @ u - b)
    beyond, drop = strain["u0"]
    assert beyond == pytest.approx(free[0], abs=1e-12) and "u1" not in strain
    expected = 1.0 - np.linalg.norm(a @ free - b) / np.linalg.norm(a @ u - b)
    assert drop == pytest.approx(expected, rel=1e-10)
