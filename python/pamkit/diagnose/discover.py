"""Discovery of what the catalog lacks: sparse regression of a channel's residual on a library of
physically meaningful terms, chosen by held-out error.

When no catalog effect explains the residual (``cause`` is ``"unexplained"``), the residual
``measured - predicted`` of a channel is fitted as a sum of a few terms from a library built
from the record itself — Coulomb friction ``p · tanh(v / v0)``, Dahl friction, viscous ``v``,
stiffness errors ``x, x², x³``, pressure, its rate and the pressurise/vent branch, the load
cell's gain and nonlinearity (F, F²), drifts in time and cycle, the gas temperature above
ambient — and reported as an equation with units, with its held-out
gain and the mechanism each term resembles::

    features = feature_library(time_s, elongation_m, pressure_kPa)
    result = discover(features, residual, sigma, fit_mask, held_mask, half_cycle, "force_N", "N")
    print(result["equation"])   # force_N residual ≈ 0.3 N/kPa · p · tanh(v / 2.1 mm/s)
    save_effect(result, "friction.json")  # discovered.py: a pamkit.Effect for the next run

Method (docs/diagnosis.md, rule 8): orthogonal matching pursuit (scikit-learn's
``orthogonal_mp``) on columns centred and scaled over the fitted samples, the offset as the
intercept; unshrunk coefficients read as physical constants; the number of terms chosen on
held-out units only, by the one-standard-error rule (Hastie, Tibshirani & Friedman, The
Elements of Statistical Learning, 2nd ed., sec. 7.10), beating no term by ``MIN_Z`` standard
errors (paired over held-out units) and by a tenth of the noise.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from scipy.signal import savgol_coeffs, savgol_filter

MAX_TERMS = 5  # an explanation with more terms is not one a reader can check
MIN_Z = 2.0  # the chosen terms must beat "no term" by 2 standard errors (one-sided ~2 %) ...
MIN_RMSE_DROP = 0.1  # ... and lower the held-out RMSE by a tenth of the noise to be worth reading
BOOTSTRAP_SAMPLES = 1000  # as the diagnosis's own gain intervals (engine.BOOTSTRAP_SAMPLES)

DERIVATIVE_WINDOW_S = 0.05  # a tensile machine turns round within tens of ms
DERIVATIVE_MIN_SAMPLES = 5  # fewest samples of the local quadratic behind a derivative
COULOMB_FRACTION = 0.05  # v0 as a share of the typical moving speed (see _coulomb_scale)
DAHL_STROKE_FRACTION = 0.05  # Dahl's slip distance as a share of the stroke: friction settles within a tenth
BRANCH_NOISE_MULTIPLE = 10.0  # pressurise/vent deadband in multiples of the pressure's noise (the range of
# 10^5 Gaussian samples is 9.6 σ: a plateau's noise does not flip it) ...
BRANCH_SPAN_FRACTION = 0.005  # ... and at least this share of its span (a noiseless simulated pressure)


@dataclass(frozen=True)
class Term:
    """One library term: a feature computable from a record, and what it stands for."""

    name: str  # e.g. "tanh(v/v0)*p"; the key that recomputes it (see _feature_columns)
    expression: str  # human readable with symbols and scales, e.g. "p · tanh(v / 1 mm/s)"
    unit: str  # unit of the feature itself, e.g. "kPa"
    resembles: str  # the physical mechanism it stands for
    parameters: tuple[tuple[str, float], ...] = ()  # data-derived scales it was computed with (v0, window, ...)


class DiscoveryError(ValueError):
    """Bad input to the discovery: names the argument and what is wrong with it."""


# --------------------------------------------------------------------------- the feature library


def _as_column(name: str, values, n: int | None, reference: str = "time_s") -> np.ndarray:
    array = np.asarray(values, dtype=float)
    if array.ndim != 1:
        raise DiscoveryError(f"{name} must be one-dimensional, got shape {array.shape}")
    if n is not None and array.size != n:
        raise DiscoveryError(f"{name} has {array.size} samples, {reference} has {n}")
    if not np.all(np.isfinite(array)):
        raise DiscoveryError(f"{name} has {int(np.sum(~np.isfinite(array)))} non-finite value(s)")
    return array


def _white_noise(values: np.ndarray) -> float:
    """Standard deviation of white noise on a smooth signal, from its second differences
    (variance 6 σ² for white noise; a smooth motion contributes little), robustly (MAD), or
    their RMS when most are zero (a quantised channel standing still)."""
    second = np.diff(values, 2)
    if second.size == 0:
        return 0.0
    typical = 1.4826 * float(np.median(np.abs(second)))
    if typical == 0.0:
        typical = float(np.sqrt(np.mean(second**2)))
    return typical / math.sqrt(6.0)


def _derivative_window(time_s: np.ndarray) -> int:
    """Odd sample count of the local quadratic behind each derivative: DERIVATIVE_WINDOW_S of
    record, at least DERIVATIVE_MIN_SAMPLES, never longer than the record."""
    dt = float(np.median(np.diff(time_s)))
    window = max(DERIVATIVE_MIN_SAMPLES, round(DERIVATIVE_WINDOW_S / dt))
    window += 1 - window % 2
    longest = time_s.size if time_s.size % 2 else time_s.size - 1
    return min(window, longest)


def _derivative(values: np.ndarray, time_s: np.ndarray, window: int) -> np.ndarray:
    """Savitzky-Golay derivative (local quadratic): encoder counts and transducer noise are
    averaged over the window instead of being differenced sample to sample."""
    dt = float(np.median(np.diff(time_s)))
    return savgol_filter(values, window, 2, deriv=1, delta=dt, mode="interp")


def _coulomb_scale(speed_mm_s: np.ndarray, elongation_noise_mm: float, window: int, dt: float) -> float:
    """v0 of tanh(v / v0) [mm/s]: COULOMB_FRACTION of the median speed while moving (samples
    faster than a tenth of the 99th-percentile speed), so tanh is within 1 % of sign(v) beyond
    three v0, i.e. 15 % of the typical speed; but at least three standard deviations of the
    speed's noise (the encoder's noise through the derivative's weights), so that the sign is
    not drawn from noise while the crosshead holds."""
    fast = float(np.percentile(speed_mm_s, 99))
    moving = speed_mm_s[speed_mm_s > 0.1 * fast]
    typical = float(np.median(moving)) if moving.size else fast
    speed_noise = elongation_noise_mm * float(np.linalg.norm(savgol_coeffs(window, 2, deriv=1, delta=dt)))
    return max(COULOMB_FRACTION * typical, 3.0 * speed_noise)


def _first_reversal(signal: np.ndarray, start: int, state: float, deadband: float) -> tuple[int, float]:
    """(index, new state) of the first reversal at or after `start`: the signal more than the
    deadband below its running maximum since `start` while not falling, or above its running
    minimum while not rising; (size, state) if there is none. Searched in windows that double,
    so a record with many reversals is not scanned to its end for each."""
    window = 256
    while True:
        segment = signal[start : start + window]
        fall = np.maximum.accumulate(segment) - segment > deadband if state >= 0.0 else np.zeros(0, bool)
        rise = segment - np.minimum.accumulate(segment) > deadband if state <= 0.0 else np.zeros(0, bool)
        first_fall = int(np.argmax(fall)) if fall.any() else segment.size
        first_rise = int(np.argmax(rise)) if rise.any() else segment.size
        if min(first_fall, first_rise) < segment.size:
            return (start + first_fall, -1.0) if first_fall < first_rise else (start + first_rise, 1.0)
        if start + window >= signal.size:
            return signal.size, state
        window *= 2


def _branch(signal: np.ndarray, deadband: float) -> np.ndarray:
    """+1 while the signal's last change larger than the deadband was a rise, -1 after a fall,
    held through plateaus; 0 before the first such change (the record does not say). For the
    pressure: pressurising or venting, the state a friction element between bladder and braid
    remembers. The deadband keeps noise on a plateau from flipping it."""
    branch = np.zeros(signal.size)
    start, state = 0, 0.0
    while start < signal.size:
        reversal, new_state = _first_reversal(signal, start, state, deadband)
        branch[start:reversal] = state
        start, state = reversal, new_state
    return branch


def _slip_since_reversal(x_mm: np.ndarray, branch: np.ndarray) -> np.ndarray:
    """Travel [mm] since the last turning point: from the lowest point of the previous stretch
    while rising, from the highest while falling; 0 before the first reversal."""
    slip = np.zeros(x_mm.size)
    bounds = np.r_[0, np.flatnonzero(np.diff(branch) != 0) + 1, x_mm.size]
    for previous, start, end in zip(bounds[:-2], bounds[1:-1], bounds[2:]):
        before = x_mm[previous:start]
        turn = before.min() if branch[start] > 0 else before.max()
        slip[start:end] = np.abs(x_mm[start:end] - turn)
    return slip


MOTION_TERMS = ("tanh(v/v0)*p", "tanh(v/v0)", "dahl(x; xc)", "v", "|v|")


def _feature_columns(
    time_s,
    elongation_m,
    pressure_kPa,
    temperature_C,
    ambient_C,
    cycle,
    force_N,
    include_motion: bool,
    scales: dict[str, float] | None = None,
) -> list[tuple[Term, np.ndarray]]:
    """Every library column the inputs allow, in a fixed order (of duplicates, feature_library
    keeps the first). `scales` (from Term.parameters) reuses a fitted record's v0, derivative
    window and deadband instead of deriving them from this record."""
    scales = dict(scales or {})
    n = time_s.size
    dt = float(np.median(np.diff(time_s)))
    window = int(scales.get("window_samples", _derivative_window(time_s)))
    with_window = (("window_samples", float(window)),)
    x_mm = 1e3 * elongation_m
    offset = Term("offset", "1", "1", "a zero offset of the channel (load-cell tare, transducer or thermometer offset)")
    columns: list[tuple[Term, np.ndarray]] = [(offset, np.ones(n))]
    if include_motion:
        v_mm_s = _derivative(x_mm, time_s, window)
        v0 = scales.get("v0_mm_per_s") or _coulomb_scale(np.abs(v_mm_s), _white_noise(x_mm), window, dt)
        if v0 > 0.0:
            coulomb = np.tanh(v_mm_s / v0)
            with_v0 = (("v0_mm_per_s", float(v0)),) + with_window
            if pressure_kPa is not None:
                columns.append(
                    (
                        Term(
                            "tanh(v/v0)*p",
                            f"p · tanh(v / {v0:.3g} mm/s)",
                            "kPa",
                            "Coulomb friction between fibres and bladder (pressure-proportional)",
                            with_v0,
                        ),
                        pressure_kPa * coulomb,
                    )
                )
            columns.append(
                (
                    Term(
                        "tanh(v/v0)",
                        f"tanh(v / {v0:.3g} mm/s)",
                        "1",
                        "Coulomb friction of constant size (fixture, guides, seals)",
                        with_v0,
                    ),
                    coulomb,
                )
            )
        # Dahl friction: after each reversal it goes from -Fc to +Fc over a slip distance xc,
        # F = Fc · d · (1 - 2 exp(-s / xc)), the exact solution of dF/dx = (Fc - d F) / xc.
        slip_deadband = scales.get("slip_deadband_mm") or max(
            BRANCH_SPAN_FRACTION * float(np.ptp(x_mm)), BRANCH_NOISE_MULTIPLE * _white_noise(x_mm)
        )
        xc = scales.get("xc_mm") or DAHL_STROKE_FRACTION * float(np.ptp(x_mm))
        if slip_deadband > 0.0 and xc > 0.0:
            stretching = _branch(x_mm, slip_deadband)
            dahl = stretching * (1.0 - 2.0 * np.exp(-_slip_since_reversal(x_mm, stretching) / xc))
            columns.append(
                (
                    Term(
                        "dahl(x; xc)",
                        f"dahl(x; {xc:.3g} mm)",
                        "1",
                        "friction that builds up over a slip distance after each reversal (Dahl, pre-sliding)",
                        (("slip_deadband_mm", float(slip_deadband)), ("xc_mm", float(xc))),
                    ),
                    dahl,
                )
            )
        columns += [
            (Term("v", "v", "mm/s", "viscous damping (force proportional to the stretch rate)", with_window), v_mm_s),
            (
                Term(
                    "|v|", "|v|", "mm/s", "a direction-independent rate effect (rate-dependent stiffening)", with_window
                ),
                np.abs(v_mm_s),
            ),
        ]
    columns += [
        (Term("x", "x", "mm", "a linear stiffness error (bladder modulus, fixture compliance, crosshead scale)"), x_mm),
        (Term("x^2", "x²", "mm²", "a stiffness that changes with stretch (bladder hardening or softening)"), x_mm**2),
        (
            Term("x^3", "x³", "mm³", "a nonlinear spring (strain stiffening of the bladder, a nonlinear load cell)"),
            x_mm**3,
        ),
    ]
    if pressure_kPa is not None:
        deadband = scales.get("deadband_kPa") or max(
            BRANCH_SPAN_FRACTION * float(np.ptp(pressure_kPa)), BRANCH_NOISE_MULTIPLE * _white_noise(pressure_kPa)
        )
        branch = _branch(pressure_kPa, deadband) if deadband > 0.0 else np.zeros(n)
        with_deadband = (("deadband_kPa", float(deadband)),)
        columns += [
            (
                Term("p", "p", "kPa", "proportional to pressure (effective area; a transducer's gain error)"),
                pressure_kPa,
            ),
            (
                Term("dp/dt", "dp/dt", "kPa/s", "a lag behind the pressure (gas dynamics, sensor lag)", with_window),
                _derivative(pressure_kPa, time_s, window),
            ),
            (
                Term(
                    "sign(dp/dt)",
                    f"branch(p; {deadband:.3g} kPa)",
                    "1",
                    "pressurise/vent hysteresis of constant size (+1 pressurising, -1 venting)",
                    with_deadband,
                ),
                branch,
            ),
            (
                Term(
                    "sign(dp/dt)*p",
                    f"p · branch(p; {deadband:.3g} kPa)",
                    "kPa",
                    "pressurise/vent hysteresis growing with pressure (bladder-braid friction at fixed length)",
                    with_deadband,
                ),
                pressure_kPa * branch,
            ),
        ]
    if force_N is not None:
        columns += [
            (Term("F", "F", "N", "a load-cell gain error (calibration scale)"), force_N),
            (Term("F^2", "F²", "N²", "a nonlinear load cell (reading curving with load)"), force_N**2),
        ]
    columns.append((Term("t", "t", "s", "a drift in time (creep, load-cell thermal drift, a slow leak)"), time_s))
    if cycle is not None:
        columns.append(
            (
                Term(
                    "cycle",
                    "cycle",
                    "cycle",
                    "a change from cycle to cycle (Mullins softening, wear, a leak per cycle)",
                ),
                cycle,
            )
        )
    if temperature_C is not None and ambient_C is not None:
        ambient = scales.get("ambient_C", float(ambient_C))
        columns.append(
            (
                Term(
                    "T-T_ambient",
                    "(T - T_ambient)",
                    "K",
                    "a thermal effect (gas heating, thermal drift of a sensor)",
                    (("ambient_C", ambient),),
                ),
                temperature_C - ambient,
            )
        )
    return columns


def feature_library(
    time_s, elongation_m, pressure_kPa=None, temperature_C=None, ambient_C=None, cycle=None, force_N=None
) -> dict[Term, np.ndarray]:
    """Physically meaningful features of a record, one array per library term.

    Args:
        time_s: sample times [s], strictly increasing.
        elongation_m: the crosshead's elongation [m]; used in millimetres (x, and v in mm/s).
        pressure_kPa: gauge pressure [kPa] (measured, or the supply), or None.
        temperature_C, ambient_C: gas and ambient temperature [°C]; both or the term is skipped.
        cycle: cycle index of every sample, or None.
        force_N: the model's predicted force [N], or None: F and F² stand for the load cell's
            gain and nonlinearity (the effect reads the simulated force in their place).

    The velocity is a Savitzky-Golay derivative (local quadratic over 50 ms, at least 5
    samples) so that encoder counts are not differenced; v0 is 5 % of the typical moving speed,
    at least three times the speed's noise (_coulomb_scale). Features whose inputs are absent
    are skipped; constant columns (other than the offset) and duplicates of an earlier column
    are dropped.

    Raises:
        DiscoveryError: naming the input of the wrong size, with non-finite values, or a time
            that does not increase.
    """
    time_s = _as_column("time_s", time_s, None)
    if time_s.size < DERIVATIVE_MIN_SAMPLES:
        raise DiscoveryError(f"time_s has {time_s.size} samples; the library needs at least {DERIVATIVE_MIN_SAMPLES}")
    not_increasing = np.flatnonzero(np.diff(time_s) <= 0.0)
    if not_increasing.size:
        raise DiscoveryError(f"time_s must increase strictly (sample {int(not_increasing[0]) + 1} does not)")
    inputs = {
        "elongation_m": elongation_m,
        "pressure_kPa": pressure_kPa,
        "temperature_C": temperature_C,
        "cycle": cycle,
        "force_N": force_N,
    }
    arrays = {key: None if value is None else _as_column(key, value, time_s.size) for key, value in inputs.items()}
    if ambient_C is not None and not math.isfinite(float(ambient_C)):
        raise DiscoveryError(f"ambient_C = {ambient_C} is not a finite temperature")
    x_mm = 1e3 * arrays["elongation_m"]
    # Travel within ten noise deviations (an isometric test's encoder) is no motion: its
    # "velocity" would be differentiated noise.
    moves = bool(np.ptp(x_mm) > 10.0 * _white_noise(x_mm))
    columns = _feature_columns(
        time_s,
        arrays["elongation_m"],
        arrays["pressure_kPa"],
        arrays["temperature_C"],
        ambient_C,
        arrays["cycle"],
        arrays["force_N"],
        include_motion=moves,
    )
    # Constant columns say what the offset says.
    varying = [
        (term, values)
        for term, values in columns
        if term.name == "offset" or np.ptp(values) > 1e-12 * max(float(np.max(np.abs(values))), 1e-300)
    ]
    # Of columns that are the same up to a factor (p·tanh(v/v0) at constant p), keep the first.
    matrix = np.column_stack([values for _, values in varying])
    gram = matrix.T @ matrix  # one product: a BLAS call per pair is slow on a busy machine
    norms = np.sqrt(np.diag(gram))
    cosine = np.abs(gram) / np.outer(norms, norms)
    kept: list[int] = []
    for j in range(len(varying)):
        if all(cosine[j, i] <= 1.0 - 1e-10 for i in kept):
            kept.append(j)
    return dict(varying[j] for j in kept)


# --------------------------------------------------------------------------- the regression


def _per(channel_unit: str, term_unit: str) -> str:
    """Unit of a coefficient: channel unit per term unit."""
    if term_unit == "1":
        return channel_unit
    if term_unit == channel_unit:
        return "1"  # a gain error: the pressure channel against p
    if term_unit == f"{channel_unit}²":
        return f"1/{channel_unit}"  # the force channel against F²
    return f"{channel_unit}/({term_unit})" if "/" in term_unit else f"{channel_unit}/{term_unit}"


def _equation(channel: str, terms: list[dict]) -> str:
    if not terms:
        return f"{channel} residual ≈ 0 (no term beats zero on held-out data)"
    parts = []
    for k, term in enumerate(terms):
        coefficient = term["coefficient"]
        sign = ("- " if coefficient < 0 else "+ ") if k else ("-" if coefficient < 0 else "")
        factor = "" if term["name"] == "offset" else f" · {term['expression']}"
        unit = "" if term["unit"] == "1" else f" {term['unit']}"
        parts.append(f"{sign}{abs(coefficient):.3g}{unit}{factor}")
    return f"{channel} residual ≈ " + " ".join(parts)


def _check_mask(name: str, mask, n: int) -> np.ndarray:
    array = np.asarray(mask)
    if array.dtype != bool or array.shape != (n,):
        raise DiscoveryError(f"{name} must be a boolean array of {n} samples, got {array.dtype} of shape {array.shape}")
    return array


def _least_squares(design: np.ndarray, target: np.ndarray) -> np.ndarray:
    return np.linalg.lstsq(design, target, rcond=None)[0]


def _candidate_models(terms: list[Term], X_fit: np.ndarray, residual_fit: np.ndarray) -> list[list[int]]:
    """Nested models, fewest terms first: none; the offset alone; then the offset with the
    first 1, 2, ... MAX_TERMS terms that orthogonal matching pursuit picks from the other
    columns centred on the fitted samples. Centring leaves the offset to the intercept: with raw
    columns every term of positive mean (pressure, x²) would stand in for an offset before the
    offset itself is picked. Without an offset column: none, then the pursuit on raw columns."""
    # Imported here: scikit-learn takes about a second to import, and most diagnoses end with a
    # named cause or none and never get here.
    from sklearn.linear_model import orthogonal_mp

    offset = next((j for j, t in enumerate(terms) if t.name == "offset"), None)
    others = np.array([j for j in range(len(terms)) if j != offset])
    columns = X_fit[:, others]
    target = residual_fit
    if offset is not None:
        columns = columns - columns.mean(axis=0)
        target = residual_fit - residual_fit.mean()
    # OMP assumes unit-norm columns; a column constant on the fitted samples cannot be picked.
    norms = np.linalg.norm(columns, axis=0)
    usable = norms > 1e-12 * max(float(norms.max(initial=0.0)), 1e-300)
    candidates = others[usable]
    models: list[list[int]] = [[]] + ([[offset]] if offset is not None else [])
    if candidates.size:
        with warnings.catch_warnings():
            # Ending early because the rest is linearly dependent is a shorter path, not an error.
            warnings.filterwarnings(
                "ignore", message="Orthogonal matching pursuit ended prematurely", category=RuntimeWarning
            )
            path = orthogonal_mp(
                columns[:, usable] / norms[usable],
                target,
                n_nonzero_coefs=min(MAX_TERMS, int(candidates.size)),
                return_path=True,
            )
        path = path.reshape(candidates.size, -1)
        for step in range(path.shape[1]):
            chosen = candidates[np.flatnonzero(path[:, step])].tolist()
            models.append(chosen + ([offset] if offset is not None else []))
    return models


def discover(
    features: dict[Term, np.ndarray],
    residual: np.ndarray,
    noise_sigma: float,
    fit_mask: np.ndarray,
    held_mask: np.ndarray,
    held_units: np.ndarray,
    channel: str,
    channel_unit: str,
    seed: int = 0,
) -> dict:
    """Sparse regression of one channel's residual on the feature library.

    Args:
        features: feature_library's output (on all samples).
        residual: measured - predicted of the channel [channel_unit], on all samples.
        noise_sigma: the channel's white-noise standard deviation [channel_unit]; gives each
            coefficient's standard error and the gain a perfect explanation would reach.
        fit_mask, held_mask: samples to fit on and samples to judge on (disjoint).
        held_units: unit id of every sample (half-cycle, sweep); held-out errors are compared
            and bootstrapped over the units in held_mask.
        channel, channel_unit: e.g. "force_N", "N".
        seed: of the bootstrap.

    Returns:
        A JSON-ready dict: channel; terms, each with expression, coefficient, unit (of the
        coefficient), resembles, standard_error, name, parameters; gain and gain_ci95 per
        channel (held-out, 1 - rmse(residual - fit) / rmse(residual)); gain_attainable (1 -
        noise_sigma / rmse(residual), the gain of a perfect explanation); heldout_rmse_path,
        the held-out RMSE of the candidates (no term, the offset, then the offset with 1, 2, ...
        terms); equation. No term that beats zero on held-out data: terms [], gain 0.

    Raises:
        DiscoveryError: naming the argument of the wrong size or type, or too few held-out units.
    """
    residual = _as_column("residual", residual, None)
    n = residual.size
    fit_mask = _check_mask("fit_mask", fit_mask, n)
    held_mask = _check_mask("held_mask", held_mask, n)
    if np.any(fit_mask & held_mask):
        raise DiscoveryError(f"fit_mask and held_mask share {int(np.sum(fit_mask & held_mask))} sample(s)")
    held_units = np.asarray(held_units)
    if held_units.shape != (n,):
        raise DiscoveryError(f"held_units has shape {held_units.shape}, residual has {n} samples")
    if not (math.isfinite(noise_sigma) and noise_sigma > 0.0):
        raise DiscoveryError(f"noise_sigma = {noise_sigma} must be a positive number")
    terms = list(features)
    if not terms:
        raise DiscoveryError("features is empty: feature_library found no term to try")
    X = np.column_stack([_as_column(f"feature {t.name}", features[t], n, "residual") for t in terms])
    units, unit_of_sample = np.unique(held_units[held_mask], return_inverse=True)
    if units.size < 2:
        raise DiscoveryError(f"held_mask covers {units.size} unit(s); judging a term needs at least 2 held-out units")
    if int(fit_mask.sum()) <= len(terms):
        raise DiscoveryError(f"fit_mask has {int(fit_mask.sum())} samples for {len(terms)} terms")

    models = _candidate_models(terms, X[fit_mask], residual[fit_mask])
    fits = [_least_squares(X[fit_mask][:, model], residual[fit_mask]) for model in models]
    held_residual = residual[held_mask]
    # Sum of squared held-out errors per candidate and unit.
    unit_sse = np.array(
        [
            np.bincount(unit_of_sample, weights=(held_residual - X[held_mask][:, model] @ c) ** 2, minlength=units.size)
            for model, c in zip(models, fits)
        ]
    )
    total = unit_sse.sum(axis=1)

    def standard_error(a: int, b: int) -> float:
        difference = unit_sse[a] - unit_sse[b]
        return float(math.sqrt(units.size) * np.std(difference, ddof=1))

    rmse = np.sqrt(total / held_residual.size)
    material = MIN_RMSE_DROP * noise_sigma

    def as_good_as_best(k: int) -> bool:
        """Candidate k is within one standard error of the best, or short of it by less than matters."""
        return total[k] - total[best] <= standard_error(k, best) or rmse[k] - rmse[best] <= material

    def beats_nothing(k: int) -> bool:
        return total[0] - total[k] > MIN_Z * standard_error(0, k) and rmse[0] - rmse[k] > material

    best = int(np.argmin(total))
    # The fewest terms that are as good as the best and beat no term at all.
    chosen = next((k for k in range(1, best + 1) if as_good_as_best(k) and beats_nothing(k)), 0)

    attainable = 1.0 - noise_sigma / rmse[0] if rmse[0] > 0 else 0.0
    result = {
        "channel": channel,
        "channel_unit": channel_unit,
        "terms": [],
        "gain": {channel: 0.0},
        "gain_ci95": {channel: [0.0, 0.0]},
        "gain_attainable": {channel: float(attainable)},
        "heldout_rmse_path": [float(value) for value in rmse],
        "equation": _equation(channel, []),
    }
    if chosen == 0:
        return result

    model, coefficients, chosen_sse = models[chosen], fits[chosen], unit_sse[chosen]
    offset = next((j for j, t in enumerate(terms) if t.name == "offset"), None)
    if offset in model and len(model) > 1:
        # The path carries an offset with every model; keep it only if it matters on held-out data.
        without = [j for j in model if j != offset]
        c = _least_squares(X[fit_mask][:, without], residual[fit_mask])
        sse = np.bincount(
            unit_of_sample, weights=(held_residual - X[held_mask][:, without] @ c) ** 2, minlength=units.size
        )
        if math.sqrt(sse.sum() / held_residual.size) - rmse[chosen] <= material:
            model, coefficients, chosen_sse = without, c, sse

    design = X[fit_mask][:, model]
    # White-noise standard errors of the least-squares coefficients.
    covariance = noise_sigma**2 * np.linalg.inv(design.T @ design)
    found = []
    for j, column in enumerate(model):
        term, coefficient = terms[column], float(coefficients[j])
        size = abs(coefficient) * float(np.sqrt(np.mean(X[held_mask, column] ** 2)))
        found.append(
            (
                size,
                {
                    "expression": term.expression,
                    "coefficient": coefficient,
                    "unit": _per(channel_unit, term.unit),
                    "resembles": term.resembles,
                    "standard_error": float(math.sqrt(covariance[j, j])),
                    "name": term.name,
                    "parameters": dict(term.parameters),
                },
            )
        )
    reported = [entry for _, entry in sorted(found, key=lambda pair: -pair[0])]  # largest contribution first

    rng = np.random.default_rng(seed)
    draws = rng.integers(0, units.size, size=(BOOTSTRAP_SAMPLES, units.size))
    boot_fit = chosen_sse[draws].sum(axis=1)
    boot_zero = unit_sse[0][draws].sum(axis=1)
    boot_gain = 1.0 - np.sqrt(boot_fit / np.maximum(boot_zero, 1e-300))
    result.update(
        {
            "terms": reported,
            "gain": {channel: float(1.0 - math.sqrt(chosen_sse.sum() / total[0]))},
            "gain_ci95": {channel: [float(np.percentile(boot_gain, 2.5)), float(np.percentile(boot_gain, 97.5))]},
            "equation": _equation(channel, reported),
        }
    )
    return result
