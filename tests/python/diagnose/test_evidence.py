"""The residual evidence's lagged cross-correlation (an FFT and cumulative sums) against its
definition, computed directly lag by lag."""

import numpy as np
import pytest

from pamkit.diagnosis.evidence import lagged_correlation_peak, lagged_correlations


def direct_lagged_correlations(residual, signal, max_lag):
    """The definition: at lag k >= 0, residual[k:] against signal[:n - k]; at k < 0,
    residual[:k] against signal[-k:]; Pearson over the overlap, both centred on whole means."""
    r = residual - residual.mean()
    x = signal - signal.mean()
    out = []
    for lag in range(-max_lag, max_lag + 1):
        a, b = (r[lag:], x[: x.size - lag]) if lag >= 0 else (r[:lag], x[-lag:])
        denominator = np.sqrt(np.dot(a, a) * np.dot(b, b))
        out.append(np.dot(a, b) / denominator if denominator > 0 else 0.0)
    return np.array(out)


@pytest.mark.parametrize("n, max_lag", [(50, 12), (1001, 250), (4096, 1024)])
def test_fft_correlations_match_the_direct_definition(n, max_lag):
    rng = np.random.default_rng(n)
    signal = rng.normal(size=n).cumsum()  # a random walk: correlated over many lags
    residual = 0.3 * np.roll(signal, 7) + rng.normal(size=n)
    fast = lagged_correlations(residual, signal, max_lag)
    # Rounding only: products of unit-scale values summed over <= 4096 terms, in another order.
    np.testing.assert_allclose(fast, direct_lagged_correlations(residual, signal, max_lag), rtol=0, atol=1e-9)


def test_peak_finds_a_known_delay():
    # The residual is the rate delayed by 25 samples (0.25 s at 100 Hz) plus noise.
    rng = np.random.default_rng(3)
    time = np.arange(5000) * 0.01
    rate = np.convolve(rng.normal(size=time.size), np.ones(20) / 20, mode="same")
    residual = np.concatenate([np.zeros(25), rate[:-25]]) + 0.1 * rng.normal(size=time.size)
    assert lagged_correlation_peak(residual, rate, time) == pytest.approx(0.25)


def test_peak_of_an_uncorrelatable_residual_is_zero_lag():
    time = np.arange(100) * 0.1
    assert lagged_correlation_peak(np.zeros(100), np.sin(time), time) == 0.0
