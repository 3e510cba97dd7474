"""The library of physical terms that discovery (discover.py) regresses a residual on, each
computed from a record's time, elongation, pressure, temperature, cycle and predicted force:
Coulomb friction ``p · tanh(v / v0)``, Dahl friction, viscous ``v``, stiffness errors ``x, x², x³``,
pressure, its rate and the pressurise/vent branch, the load cell's gain and nonlinearity (F, F²),
drifts in time and cycle, the gas temperature above ambient.

The record comes in SI, and the pressure's terms stay in it (p in Pa, as the channels it is
regressed against); the crosshead's are in millimetres (x in mm, v in mm/s), the scale of a
bench's stroke, so that a discovered equation reads in numbers a person can weigh."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pamkit.diagnosis.filters import savgol_filter, savgol_weights
from pamkit.units import MILLIMETRE_PER_METRE

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
    unit: str  # unit of the feature itself, e.g. "Pa"
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
    return savgol_filter(values, window, 2, deriv=1, delta=dt)


def _coulomb_scale(speed_mm_s: np.ndarray, elongation_noise_mm: float, window: int, dt: float) -> float:
    """v0 of tanh(v / v0) [mm/s]: COULOMB_FRACTION of the median speed while moving (samples
    faster than a tenth of the 99th-percentile speed), so tanh is within 1 % of sign(v) beyond
    three v0, i.e. 15 % of the typical speed; but at least three standard deviations of the
    speed's noise (the encoder's noise through the derivative's weights), so that the sign is
    not drawn from noise while the crosshead holds."""
    fast = float(np.percentile(speed_mm_s, 99))
    moving = speed_mm_s[speed_mm_s > 0.1 * fast]
    typical = float(np.median(moving)) if moving.size else fast
    speed_noise = elongation_noise_mm * float(np.linalg.norm(savgol_weights(window, 2, deriv=1, delta=dt)))
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
    gauge_pressure_Pa,
    temperature_K,
    ambient_K,
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
    x_mm = MILLIMETRE_PER_METRE * elongation_m
    offset = Term("offset", "1", "1", "a zero offset of the channel (load-cell tare, transducer or thermometer offset)")
    columns: list[tuple[Term, np.ndarray]] = [(offset, np.ones(n))]
    if include_motion:
        v_mm_s = _derivative(x_mm, time_s, window)
        v0 = scales.get("v0_mm_per_s") or _coulomb_scale(np.abs(v_mm_s), _white_noise(x_mm), window, dt)
        if v0 > 0.0:
            coulomb = np.tanh(v_mm_s / v0)
            with_v0 = (("v0_mm_per_s", float(v0)),) + with_window
            if gauge_pressure_Pa is not None:
                columns.append(
                    (
                        Term(
                            "tanh(v/v0)*p",
                            f"p · tanh(v / {v0:.3g} mm/s)",
                            "Pa",
                            "Coulomb friction between fibres and bladder (pressure-proportional)",
                            with_v0,
                        ),
                        gauge_pressure_Pa * coulomb,
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
    if gauge_pressure_Pa is not None:
        deadband = scales.get("deadband_Pa") or max(
            BRANCH_SPAN_FRACTION * float(np.ptp(gauge_pressure_Pa)),
            BRANCH_NOISE_MULTIPLE * _white_noise(gauge_pressure_Pa),
        )
        branch = _branch(gauge_pressure_Pa, deadband) if deadband > 0.0 else np.zeros(n)
        with_deadband = (("deadband_Pa", float(deadband)),)
        columns += [
            (
                Term("p", "p", "Pa", "proportional to pressure (effective area; a transducer's gain error)"),
                gauge_pressure_Pa,
            ),
            (
                Term(
                    "dp/dt",
                    "dp/dt",
                    "Pa/s",
                    "a lag behind the pressure (gas dynamics, sensor lag)",
                    with_window,
                ),
                _derivative(gauge_pressure_Pa, time_s, window),
            ),
            (
                Term(
                    "sign(dp/dt)",
                    f"branch(p; {deadband:.3g} Pa)",
                    "1",
                    "pressurise/vent hysteresis of constant size (+1 pressurising, -1 venting)",
                    with_deadband,
                ),
                branch,
            ),
            (
                Term(
                    "sign(dp/dt)*p",
                    f"p · branch(p; {deadband:.3g} Pa)",
                    "Pa",
                    "pressurise/vent hysteresis growing with pressure (bladder-braid friction at fixed length)",
                    with_deadband,
                ),
                gauge_pressure_Pa * branch,
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
    if temperature_K is not None and ambient_K is not None:
        ambient = scales.get("ambient_K", float(ambient_K))
        columns.append(
            (
                Term(
                    "T-T_ambient",
                    "(T - T_ambient)",
                    "K",
                    "a thermal effect (gas heating, thermal drift of a sensor)",
                    (("ambient_K", ambient),),
                ),
                temperature_K - ambient,
            )
        )
    return columns


def feature_library(
    time_s, elongation_m, gauge_pressure_Pa=None, temperature_K=None, ambient_K=None, cycle=None, force_N=None
) -> dict[Term, np.ndarray]:
    """Physically meaningful features of a record, one array per library term.

    Args:
        time_s: sample times [s], strictly increasing.
        elongation_m: the crosshead's elongation [m]; used in millimetres (x, and v in mm/s).
        gauge_pressure_Pa: gauge pressure [Pa] (measured, or the supply), or None.
        temperature_K, ambient_K: gas and ambient temperature [K]; both or the term is skipped.
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
        "gauge_pressure_Pa": gauge_pressure_Pa,
        "temperature_K": temperature_K,
        "cycle": cycle,
        "force_N": force_N,
    }
    arrays = {key: None if value is None else _as_column(key, value, time_s.size) for key, value in inputs.items()}
    if ambient_K is not None and not math.isfinite(float(ambient_K)):
        raise DiscoveryError(f"ambient_K = {ambient_K} is not a finite temperature")
    x_mm = MILLIMETRE_PER_METRE * arrays["elongation_m"]
    # Travel within ten noise deviations (an isometric test's encoder) is no motion: its
    # "velocity" would be differentiated noise.
    moves = bool(np.ptp(x_mm) > 10.0 * _white_noise(x_mm))
    columns = _feature_columns(
        time_s,
        arrays["elongation_m"],
        arrays["gauge_pressure_Pa"],
        arrays["temperature_K"],
        ambient_K,
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
