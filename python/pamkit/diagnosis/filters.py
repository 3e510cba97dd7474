"""The few signal filters diagnosis uses, written on numpy and scipy.fft: Savitzky-Golay smoothing
and differentiation, a running median and a full cross-correlation.

They are the same filters as scipy.signal.savgol_filter (mode "interp"), savgol_coeffs,
scipy.ndimage.median_filter (mode "nearest") and scipy.signal.correlate (method "fft"), to
rounding. Importing scipy.signal, which brings scipy.stats with it, costs three quarters of what
importing scipy.optimize costs, more than all else the diagnosis imports; a user would pay it at
every start of `pamkit diagnose` (bench/bench_import.py)."""

from __future__ import annotations

import math

import numpy as np
import scipy.fft
from numpy.lib.stride_tricks import sliding_window_view


def _polynomial_weights(window: int, polyorder: int, deriv: int, delta: float, positions: np.ndarray) -> np.ndarray:
    """Rows of weights, one per sample position of the window: the derivative of order `deriv` of
    the least-squares polynomial through the window's samples, at that position, is the row's
    dot product with the samples."""
    offsets = np.arange(window) - window // 2  # from the centre: a better-conditioned fit
    powers = np.arange(polyorder + 1)
    # The polynomial's coefficients in powers of the offset are pinv(V) @ samples, V[j, k] = offset_j**k.
    fit = np.linalg.pinv(offsets[:, np.newaxis] ** powers.astype(float))
    # d^deriv/dx^deriv x**k = k! / (k - deriv)! x**(k - deriv), zero for k < deriv.
    falling = np.array([math.perm(k, deriv) for k in powers], dtype=float)
    at = (np.asarray(positions) - window // 2).astype(float)
    derivative = falling * at[:, np.newaxis] ** np.clip(powers - deriv, 0, None)
    return derivative @ fit / delta**deriv


def savgol_weights(window: int, polyorder: int, deriv: int = 0, delta: float = 1.0) -> np.ndarray:
    """Weights of a Savitzky-Golay filter: the least-squares polynomial of degree `polyorder`
    through `window` equally spaced samples, its derivative of order `deriv` at the centre sample.

    Parameters
    ----------
    window : int
        Odd number of samples the polynomial is fitted to.
    polyorder : int
        Degree of the polynomial, below `window`.
    deriv : int
        Order of the derivative (0: the smoothed value).
    delta : float
        Spacing of the samples, in the unit the derivative is taken in (s for a rate).

    Returns
    -------
    numpy.ndarray
        `window` weights in the samples' order: the value is ``weights @ samples``.
    """
    return _polynomial_weights(window, polyorder, deriv, delta, np.array([window // 2]))[0]


def savgol_filter(values: np.ndarray, window: int, polyorder: int, deriv: int = 0, delta: float = 1.0) -> np.ndarray:
    """Savitzky-Golay smoothing (or derivative) of a series: at each sample the least-squares
    polynomial through the `window` samples centred on it; within half a window of either end,
    the polynomial through the first (last) `window` samples, at that sample.

    Parameters
    ----------
    values : numpy.ndarray
        The series, equally spaced, at least `window` samples.
    window : int
        Odd number of samples of each fit.
    polyorder : int
        Degree of the polynomial, below `window`.
    deriv : int
        Order of the derivative (0: the smoothed series).
    delta : float
        Spacing of the samples, in the unit the derivative is taken in (s for a rate).

    Returns
    -------
    numpy.ndarray
        The filtered series, as long as `values`.
    """
    y = np.asarray(values, dtype=float)
    if window % 2 == 0 or window > y.size:
        raise ValueError(f"savgol_filter: window {window} must be odd and at most the series' {y.size} samples")
    half = window // 2
    weights = _polynomial_weights(window, polyorder, deriv, delta, np.arange(window))
    out = np.empty_like(y)
    out[half : y.size - half] = np.correlate(y, weights[half], mode="valid")
    out[:half] = weights[:half] @ y[:window]
    out[y.size - half :] = weights[half + 1 :] @ y[-window:]
    return out


def running_median(values: np.ndarray, size: int) -> np.ndarray:
    """Median of the `size` samples centred on each sample (odd `size`), the series extended
    beyond each end by repeating its end sample.

    Parameters
    ----------
    values : numpy.ndarray
        The series.
    size : int
        Odd number of samples in each median.

    Returns
    -------
    numpy.ndarray
        The filtered series, as long as `values`.
    """
    if size % 2 == 0:
        raise ValueError(f"running_median: size {size} must be odd")
    padded = np.pad(np.asarray(values, dtype=float), size // 2, mode="edge")
    return np.median(sliding_window_view(padded, size), axis=-1)


def cross_correlation(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Full cross-correlation of two series by FFT: element ``b.size - 1 + k`` is
    ``sum_i a[i + k] * b[i]`` over the samples both have, for every k from ``-(b.size - 1)`` to
    ``a.size - 1``.

    Parameters
    ----------
    a, b : numpy.ndarray
        The two series.

    Returns
    -------
    numpy.ndarray
        ``a.size + b.size - 1`` products.
    """
    size = a.size + b.size - 1
    length = scipy.fft.next_fast_len(size, real=True)
    spectrum = scipy.fft.rfft(a, length) * scipy.fft.rfft(b[::-1], length)
    return scipy.fft.irfft(spectrum, length)[:size]
