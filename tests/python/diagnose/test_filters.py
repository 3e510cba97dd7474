"""The diagnosis's numpy filters (pamkit.diagnosis.filters) against the scipy calls they stand for:
the same numbers to rounding, and exactly where the operation selects or sums the same terms."""

import numpy as np
import pytest
import scipy.ndimage
import scipy.signal
import scipy.special
import scipy.stats

from pamkit.diagnosis.evidence import ljung_box_p
from pamkit.diagnosis.filters import cross_correlation, running_median, savgol_filter, savgol_weights

EPS = np.finfo(float).eps

# (window, polyorder, deriv, delta) as diagnosis calls them: the noise's local cubic
# (evidence.noise_scale), the crosshead's smoothing (motion.programmed_motion) and the rates of
# discovery's terms (features._derivative, a quadratic over 0.05 s at 10 Hz to 1 kHz).
DIAGNOSIS_FILTERS = [(9, 3, 0, 1.0), (9, 2, 0, 1.0), (5, 2, 1, 0.1), (13, 2, 1, 0.004), (51, 2, 1, 0.001)]


def rounding_bound(window: int, polyorder: int, weights: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Bound on two roundings of one least-squares filter: its weights solved by two
    factorisations of the Vandermonde matrix V (relative error up to cond(V) eps each), then
    summed over the window in two orders (up to window eps relative to the sum of |terms|)."""
    offsets = np.arange(window) - window // 2
    condition = np.linalg.cond(offsets[:, np.newaxis] ** np.arange(polyorder + 1.0))
    terms = np.convolve(np.abs(values), np.abs(weights), mode="same")  # sum of |w_j y_j| at each sample
    return 2.0 * (condition + window) * EPS * np.maximum(terms, np.max(terms))


def random_walk(seed: int, size: int = 400) -> np.ndarray:
    """A crosshead-like series: a random walk on an offset (the offset makes the sums cancel)."""
    return 100.0 + np.cumsum(np.random.default_rng(seed).normal(size=size))


@pytest.mark.parametrize("window, polyorder, deriv, delta", DIAGNOSIS_FILTERS)
def test_savgol_weights_are_scipys(window, polyorder, deriv, delta):
    ours = savgol_weights(window, polyorder, deriv, delta)
    theirs = scipy.signal.savgol_coeffs(window, polyorder, deriv=deriv, delta=delta, use="dot")
    offsets = np.arange(window) - window // 2
    condition = np.linalg.cond(offsets[:, np.newaxis] ** np.arange(polyorder + 1.0))
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=2 * condition * EPS * np.max(np.abs(theirs)))


@pytest.mark.parametrize("window, polyorder, deriv, delta", DIAGNOSIS_FILTERS)
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_savgol_filter_is_scipys_interp_mode(window, polyorder, deriv, delta, seed):
    values = random_walk(seed)
    ours = savgol_filter(values, window, polyorder, deriv, delta)
    theirs = scipy.signal.savgol_filter(values, window, polyorder, deriv=deriv, delta=delta, mode="interp")
    weights = savgol_weights(window, polyorder, deriv, delta)
    assert np.all(np.abs(ours - theirs) <= rounding_bound(window, polyorder, weights, values))


def test_savgol_filter_on_a_record_as_long_as_its_window():
    """The shortest record features._derivative filters: one window, every sample an edge."""
    values = random_walk(4, size=13)
    ours = savgol_filter(values, 13, 2, 1, 0.004)
    theirs = scipy.signal.savgol_filter(values, 13, 2, deriv=1, delta=0.004, mode="interp")
    assert np.all(np.abs(ours - theirs) <= rounding_bound(13, 2, savgol_weights(13, 2, 1, 0.004), values))


def test_savgol_filter_keeps_a_polynomial_of_its_order():
    """An invariant apart from scipy: the least-squares cubic through samples of a cubic is that
    cubic, at the edges too, and its derivative the cubic's derivative."""
    t = np.linspace(-1.0, 2.0, 61)
    dt = t[1] - t[0]
    cubic = 0.3 - 1.2 * t + 0.7 * t**2 + 0.25 * t**3
    np.testing.assert_allclose(savgol_filter(cubic, 9, 3), cubic, rtol=0, atol=1e-12)
    np.testing.assert_allclose(savgol_filter(cubic, 9, 3, 1, dt), -1.2 + 1.4 * t + 0.75 * t**2, rtol=0, atol=1e-10)


def test_savgol_filter_refuses_a_window_it_cannot_centre():
    with pytest.raises(ValueError, match="window 8 must be odd"):
        savgol_filter(np.zeros(20), 8, 2)
    with pytest.raises(ValueError, match="at most the series' 5 samples"):
        savgol_filter(np.zeros(5), 9, 2)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_running_median_is_scipys_nearest_mode_exactly(seed):
    """A median of an odd count selects one of the samples: no rounding, the same numbers."""
    values = np.random.default_rng(seed).normal(size=300)
    values[::7] = values[3]  # ties, as a quantised plateau has
    np.testing.assert_array_equal(
        running_median(values, 5), scipy.ndimage.median_filter(values, size=5, mode="nearest")
    )


@pytest.mark.parametrize("sizes", [(500, 500), (313, 97), (1, 40)])
def test_cross_correlation_is_the_direct_sum(sizes):
    """Against numpy's direct sum (the same definition, O(n m)) and scipy.signal's FFT route: an
    FFT product is off the direct sum by up to a few eps log2(length) ||a|| ||b||."""
    rng = np.random.default_rng(sum(sizes))
    a, b = rng.normal(size=sizes[0]), rng.normal(size=sizes[1])
    ours = cross_correlation(a, b)
    bound = 8 * EPS * np.log2(a.size + b.size) * np.linalg.norm(a) * np.linalg.norm(b)
    np.testing.assert_allclose(ours, np.correlate(a, b, mode="full"), rtol=0, atol=bound)
    np.testing.assert_allclose(ours, scipy.signal.correlate(a, b, mode="full", method="fft"), rtol=0, atol=bound)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_ljung_box_p_is_the_chi_squared_tail(seed):
    """The p-value from scipy.special's chi-squared survival function, against scipy.stats' chi2
    on the statistic written out: n (n + 2) sum rho_k^2 / (n - k)."""
    r = np.random.default_rng(seed).normal(size=200)
    r[1:] += 0.3 * r[:-1]  # some structure: a p-value away from 1
    c = r - r.mean()
    n, lags = c.size, 20
    rho = np.array([np.sum(c[: n - k] * c[k:]) for k in range(1, lags + 1)]) / np.sum(c * c)
    q = n * (n + 2) * np.sum(rho**2 / (n - np.arange(1, lags + 1)))
    assert ljung_box_p(r, lags) == pytest.approx(scipy.stats.chi2.sf(q, lags), rel=1e-12)
