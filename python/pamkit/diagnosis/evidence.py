"""What the residuals say: their size per channel (as the thesis's tables C.5-C.8), whether
they look like noise (Ljung-Box), and what they move with (cross-correlation with elongation,
velocity, |velocity|, time and cycle index)."""

from __future__ import annotations

import numpy as np
from scipy.special import chdtrc

from pamkit.diagnosis.filters import cross_correlation, savgol_filter, savgol_weights

NOISE_WINDOW = 9  # samples in the local cubic that stands for the signal
NOISE_POLYORDER = 3


def noise_scale(values: np.ndarray) -> float:
    """Standard deviation of the white noise on a channel, from what a local cubic
    (Savitzky-Golay, 9 samples) leaves: the median absolute residual, which the friction's step
    at every turning point (tens of newtons at 50 mm/s, a quarter of the samples near it at
    25 Hz) does not move, scaled to a standard deviation and for the share of the noise the
    cubic itself follows. A quantised channel that mostly stands still (a TMP36 through a
    10-bit ADC) keeps its toggling counts as noise; if the median is zero the RMS is used."""
    v = np.asarray(values, dtype=float)
    if v.size < NOISE_WINDOW + 2:
        return max(float(np.std(v)), 1e-12)
    residual = v - savgol_filter(v, NOISE_WINDOW, NOISE_POLYORDER)
    # The cubic follows its centre weight's share of white noise's variance at each point.
    followed = float(savgol_weights(NOISE_WINDOW, NOISE_POLYORDER)[NOISE_WINDOW // 2])
    typical = 1.4826 * float(np.median(np.abs(residual)))
    if typical == 0.0:
        typical = float(np.sqrt(np.mean(residual**2)))
    return max(typical / np.sqrt(1.0 - followed), 1e-12)


def rmse(residual: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.square(residual)))) if residual.size else float("nan")


def peak_difference(measured: np.ndarray, predicted: np.ndarray, cycle_label: np.ndarray) -> float:
    """Mean over cycles of (measured peak - predicted peak), as tables C.6 and C.8 (positive:
    the measurement peaks higher)."""
    differences = [
        float(measured[cycle_label == k].max() - predicted[cycle_label == k].max())
        for k in np.unique(cycle_label[cycle_label >= 0])
    ]
    return float(np.mean(differences)) if differences else float("nan")


def ljung_box_p(residual: np.ndarray, lags: int = 20) -> float:
    """p-value of the Ljung-Box test that the residual's first `lags` autocorrelations are zero
    (small p: structure is left, not noise)."""
    r = np.asarray(residual, dtype=float) - np.mean(residual)
    n = r.size
    denominator = float(np.dot(r, r))
    if n <= lags + 1 or denominator == 0.0:
        return float("nan")
    k = np.arange(1, lags + 1)
    rho = np.array([np.dot(r[:-j], r[j:]) for j in k]) / denominator
    q = n * (n + 2) * float(np.sum(rho**2 / (n - k)))
    return float(chdtrc(lags, q))  # the chi-squared distribution's survival function


def correlations(residual: np.ndarray, regressors: dict[str, np.ndarray]) -> dict[str, float]:
    """Pearson correlation of the residual with each regressor (0 where a regressor is constant)."""
    out = {}
    r = residual - residual.mean()
    for name, x in regressors.items():
        x = x - x.mean()
        denominator = np.sqrt(np.dot(r, r) * np.dot(x, x))
        out[name] = float(np.dot(r, x) / denominator) if denominator > 0 else 0.0
    return out


def lagged_correlations(residual: np.ndarray, signal: np.ndarray, max_lag: int) -> np.ndarray:
    """Pearson correlation of the residual with the signal shifted by every lag in
    [-max_lag, max_lag] samples (element max_lag + k pairs residual[k:] with signal[:n - k], a
    negative k residual[:k] with signal[-k:]), each over the two series' overlap at that lag and
    normalised by the overlap's own sums of squares (0 where one is zero); both series are
    centred on their whole means first.

    The products at every lag come from one FFT correlation (filters.cross_correlation), the
    overlap norms from cumulative sums: O(n log n) instead of O(lags x n).
    """
    r = np.asarray(residual, dtype=float)
    x = np.asarray(signal, dtype=float)
    r = r - r.mean()
    x = x - x.mean()
    n = r.size
    lags = np.arange(-max_lag, max_lag + 1)
    # cross_correlation(r, x)[n - 1 + k] = sum_i r[i + k] x[i]: residual[k:] against signal[:n - k].
    products = cross_correlation(r, x)[n - 1 + lags]
    # Sums of squares of a prefix (cumulative from the start) and a suffix (from the end).
    r_prefix = np.concatenate([[0.0], np.cumsum(r * r)])
    x_prefix = np.concatenate([[0.0], np.cumsum(x * x)])
    overlap = n - np.abs(lags)
    r_norm = np.where(lags >= 0, r_prefix[n] - r_prefix[np.clip(lags, 0, n)], r_prefix[overlap])
    x_norm = np.where(lags >= 0, x_prefix[overlap], x_prefix[n] - x_prefix[np.clip(-lags, 0, n)])
    denominator = np.sqrt(np.clip(r_norm, 0.0, None) * np.clip(x_norm, 0.0, None))
    out = np.zeros(lags.size)
    positive = denominator > 0
    out[positive] = products[positive] / denominator[positive]
    return out


def lagged_correlation_peak(
    residual: np.ndarray, signal_rate: np.ndarray, time: np.ndarray, max_lag_s: float = 10.0
) -> float:
    """Lag [s] at which the residual correlates best (in magnitude) with the prediction's rate
    of change: near zero for noise, at the offset for a skewed or lagging channel. Of equal
    peaks, the most negative lag; 0 when nothing correlates at any lag."""
    dt = float(np.median(np.diff(time)))
    max_lag = max(1, min(int(max_lag_s / dt), residual.size // 4))
    correlation = np.abs(lagged_correlations(residual, signal_rate, max_lag))
    best = int(np.argmax(correlation))
    return float((best - max_lag) * dt) if correlation[best] > 0 else 0.0
