"""The Arduino logger's files: its calibration file, its CSV, the tensile machine's export, and
the join of the two into an experiment file.

The serial reading itself is C++ (``pamkit._core.logger.Reader``); this module holds what is
file handling and signal processing.

Every problem is a :class:`LoggerError` (a ``ValueError``) that names the file, and the line and
column for CSV data.
"""

from __future__ import annotations

import csv
import io
import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

try:
    import tomllib
except ModuleNotFoundError:  # Python < 3.11
    import tomli as tomllib

from pamkit._core.logger import LoggerCalibration, fit_pressure
from pamkit.io.columns import to_si
from pamkit.io.guards import ExperimentError
from pamkit.io.machine import read_machine_export

_DEFAULTS = LoggerCalibration()  # the host's defaults: a 5 V reference, the TMP36's datasheet line

CALIBRATION_TEMPLATE = f"""\
# pamkit logger calibration (thesis appendix B).
#
# Pressure: apply known gauge pressures to the 61CP transducer with a reference gauge, from
# 0 to 80 psi in 10 psi steps, and write the voltage read at each step (the pressure_V column
# of `pamkit log --uncalibrated`, averaged over a few seconds, or a multimeter on A0).
# pamkit fits a straight line through the points and reports the worst residual.
#
# Temperature: the TMP36 needs no calibration: T = (V - offset_V) / V_per_C.

[adc]
reference_V = {_DEFAULTS.adc_reference_V:<13} # the Mega's 5 V pin (AVCC) as measured with a multimeter [V]

[pressure]
applied_psi = [0, 10, 20, 30, 40, 50, 60, 70, 80]
measured_V = []             # fill in: one voltage per applied pressure [V]

[temperature]
offset_V = {_DEFAULTS.tmp36_offset_V:<16} # TMP36 output at 0 degC [V]
V_per_C = {_DEFAULTS.tmp36_V_per_C:<17} # TMP36 scale factor [V/degC]
"""

_CALIBRATION_KEYS = {
    "adc": {"reference_V"},
    "pressure": {"applied_psi", "measured_V"},
    "temperature": {"offset_V", "V_per_C"},
}


class LoggerError(ValueError):
    """A logger, machine or calibration file cannot be used; the message says where."""


class LoggerWarning(UserWarning):
    """Something in a logger file was left out (an unterminated last line); the message says where."""


@dataclass
class Calibration:
    """A loaded calibration file: the C++ calibration, whether pressure is calibrated, and the fit."""

    calibration: LoggerCalibration
    pressure_calibrated: bool
    max_residual_kPa: float = float("nan")


def load_calibration(path: str | Path) -> Calibration:
    """Reads a calibration file (see :data:`CALIBRATION_TEMPLATE`) and fits the pressure line.

    Raises:
        LoggerError: naming the file and the key of the first problem.
    """
    path = Path(path)
    try:
        with path.open("rb") as handle:
            document = tomllib.load(handle)
    except FileNotFoundError:
        raise LoggerError(
            f"{path}: no such calibration file (write one with `pamkit log --write-calibration-template {path}` "
            "and fill in the voltages, or log volts only with --uncalibrated)"
        ) from None
    except tomllib.TOMLDecodeError as error:
        raise LoggerError(f"{path}: not valid TOML: {error}") from None
    for section, table in document.items():
        if section not in _CALIBRATION_KEYS or not isinstance(table, dict):
            raise LoggerError(f"{path}: unknown section [{section}] (known: {', '.join(_CALIBRATION_KEYS)})")
        for key in table:
            if key not in _CALIBRATION_KEYS[section]:
                raise LoggerError(
                    f"{path}: unknown key [{section}] {key} (known: {', '.join(sorted(_CALIBRATION_KEYS[section]))})"
                )

    def number(section: str, key: str, default: float) -> float:
        value = document.get(section, {}).get(key, default)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise LoggerError(f"{path}: [{section}] {key} = {value!r} must be a finite number")
        return float(value)

    calibration = LoggerCalibration()
    calibration.adc_reference_V = number("adc", "reference_V", calibration.adc_reference_V)
    calibration.tmp36_offset_V = number("temperature", "offset_V", calibration.tmp36_offset_V)
    calibration.tmp36_V_per_C = number("temperature", "V_per_C", calibration.tmp36_V_per_C)
    pressure = document.get("pressure", {})
    psi, volts = pressure.get("applied_psi", []), pressure.get("measured_V", [])
    for key, values in (("applied_psi", psi), ("measured_V", volts)):
        if not isinstance(values, list) or not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in values
        ):
            raise LoggerError(f"{path}: [pressure] {key} must be a list of numbers")
    if not volts:
        raise LoggerError(
            f"{path}: [pressure] measured_V is empty: fill in the voltage read at each of applied_psi "
            f"({', '.join(str(p) for p in psi)} psi), or log volts only with --uncalibrated"
        )
    try:
        fit = fit_pressure([float(p) for p in psi], [float(v) for v in volts])
        calibration.pressure_kPa_per_V = fit["kPa_per_V"]
        calibration.pressure_offset_kPa = fit["offset_kPa"]
        calibration.validate()
    except ValueError as error:
        raise LoggerError(f"{path}: {error}") from None
    return Calibration(calibration, True, fit["max_residual_kPa"])


# --- reading the two logs ---------------------------------------------------------------------


def read_machine_csv(path: str | Path, specimen: str | None = None) -> dict[str, np.ndarray]:
    """Reads a tensile machine's export (Instron Bluehill, ZwickRoell testXpert, or a CSV whose
    column names carry their units: pamkit.io.machine): time_s, extension_m and force_N, of
    `specimen` (its label) in an export of several.

    Raises:
        LoggerError: naming the file, line and column of the first problem; naming the
            specimens when there are several and none (or another) is chosen.
    """
    try:
        return read_machine_export(path, specimen).columns
    except ExperimentError as error:
        raise LoggerError(str(error)) from None


def read_logger_csv(path: str | Path) -> dict[str, np.ndarray]:
    """Reads a `pamkit log` CSV (time_s, pressure_kPa, temperature_C, ...), its channels in SI
    (gauge_pressure_Pa, temperature_K: pamkit.io.columns), the raw ones (pressure_V, boot, ...)
    as they are.

    A last line without a line end is a row the logger was writing when it was stopped (killed,
    or the machine lost power, docs/logger.md): it is dropped with a :class:`LoggerWarning`
    naming the file and line, never read as a row - cut short, it could still parse as numbers.

    Raises:
        LoggerError: naming the file and line of the first problem.
    """
    path = Path(path)
    try:
        with path.open(newline="") as handle:
            text = handle.read()
    except FileNotFoundError:
        raise LoggerError(f"{path}: no such logger file") from None
    except IsADirectoryError:
        raise LoggerError(f"{path}: is a folder, not a logger file") from None
    except UnicodeDecodeError as error:
        raise LoggerError(f"{path}: not a text file (byte {error.start} is not UTF-8)") from None
    if text and not text.endswith("\n"):
        kept, _, cut = text.rpartition("\n")
        line = kept.count("\n") + 2 if kept else 1
        warnings.warn(
            f"{path}:{line}: the last line has no line end (the logger was stopped while writing it): "
            f"{cut[:60]!r} dropped",
            LoggerWarning,
            stacklevel=2,
        )
        text = kept + "\n" if kept else ""
    reader = csv.reader(io.StringIO(text, newline=""))
    header = [name.strip() for name in next(reader, [])]
    if "time_s" not in header:
        raise LoggerError(f"{path}:1: no time_s column: is this a `pamkit log` file?")
    table = []
    for row in reader:
        if not row:
            continue
        try:
            table.append([float(cell) for cell in row])
        except ValueError:
            raise LoggerError(f"{path}:{reader.line_num}: a value is not a number: {row}") from None
        if len(row) != len(header):
            raise LoggerError(f"{path}:{reader.line_num}: {len(row)} values, the header has {len(header)}")
    if len(table) < 2:
        raise LoggerError(f"{path}: needs at least 2 rows, found {len(table)}")
    data = np.asarray(table)
    out = {name: data[:, i].copy() for i, name in enumerate(header)}
    _check_time(path, out["time_s"])
    return to_si(out)


def _check_time(path: Path, time: np.ndarray) -> None:
    if time.size < 2:
        raise LoggerError(f"{path}: needs at least 2 samples")
    steps = np.diff(time)
    if np.any(steps <= 0):
        index = int(np.argmax(steps <= 0)) + 1
        raise LoggerError(
            f"{path}: time does not increase at sample {index + 1} ({time[index - 1]} -> {time[index]} s)"
        )


# --- alignment ----------------------------------------------------------------------------------


@dataclass
class Alignment:
    """How the logger's clock relates to the machine's: logger time = machine time + offset_s."""

    offset_s: float
    correlation: float  # Pearson r of the two signals at that offset, over their overlap
    next_best_ratio: float  # height of the next-best cross-correlation peak relative to the chosen one
    next_best_offset_s: float  # where that peak is
    step_s: float  # resolution of the search grid (one logger sample)
    logger_signal: str
    machine_signal: str
    notes: list[str] = field(default_factory=list)


def _zscore(values: np.ndarray) -> np.ndarray:
    spread = values.std()
    if not spread > 0:
        raise LoggerError("a signal used for alignment is constant: nothing to align on")
    return (values - values.mean()) / spread


def find_offset(
    logger_time: np.ndarray,
    logger_values: np.ndarray,
    machine_time: np.ndarray,
    machine_values: np.ndarray,
    step_s: float,
    max_offset_s: float | None = None,
) -> tuple[float, float, float, float]:
    """Offset between two signals of the same process by cross-correlation: returns
    (offset_s, r, next_best_ratio, next_best_offset_s) with logger time = machine time + offset_s,
    r the Pearson correlation over the overlap at that offset, and next_best_ratio the height of
    the best other peak of the cross-correlation relative to the chosen one (near 1: ambiguous).

    Both signals are resampled on a grid of `step_s`, standardised, and cross-correlated (FFT);
    the peak is refined by a parabola through its three grid points. The plain (not
    overlap-normalised) correlation favours the lag with the most overlap, so that a cyclic test
    does not lock onto a neighbouring cycle.
    """
    from scipy.signal import correlate  # imported where logs are aligned: it adds a third of a second to every start

    grid_l = np.arange(logger_time[0], logger_time[-1], step_s)
    grid_m = np.arange(machine_time[0], machine_time[-1], step_s)
    if grid_l.size < 3 or grid_m.size < 3:
        raise LoggerError("the logs are too short to align")
    a = _zscore(np.interp(grid_l, logger_time, logger_values))
    b = _zscore(np.interp(grid_m, machine_time, machine_values))
    c = correlate(a, b, mode="full", method="fft") / min(a.size, b.size)
    # c[k] pairs a[i + lag] with b[i], lag = k - (b.size - 1): logger grid index = machine index + lag
    lags = np.arange(c.size) - (b.size - 1)
    offsets = grid_l[0] - grid_m[0] + lags * step_s
    allowed = np.ones(c.size, bool) if max_offset_s is None else np.abs(offsets) <= max_offset_s
    if not allowed.any():
        raise LoggerError(f"no offset within ±{max_offset_s} s overlaps the two logs")
    masked = np.where(allowed, c, -np.inf)
    k = int(np.argmax(masked))
    shift = 0.0
    if 0 < k < c.size - 1 and np.isfinite(masked[k - 1]) and np.isfinite(masked[k + 1]):
        denominator = masked[k - 1] - 2 * masked[k] + masked[k + 1]
        if denominator < 0:
            shift = 0.5 * (masked[k - 1] - masked[k + 1]) / denominator
    offset = offsets[k] + shift * step_s

    # the main lobe: down to where the correlation falls to half its peak on either side
    low, high = k, k
    while low > 0 and masked[low - 1] > 0.5 * masked[k]:
        low -= 1
    while high < c.size - 1 and masked[high + 1] > 0.5 * masked[k]:
        high += 1
    outside = masked.copy()
    outside[low : high + 1] = -np.inf
    peaks = (outside[1:-1] >= outside[:-2]) & (outside[1:-1] >= outside[2:]) & np.isfinite(outside[1:-1])
    candidates = np.flatnonzero(peaks) + 1
    if candidates.size:
        j = candidates[np.argmax(outside[candidates])]
        next_offset, next_ratio = float(offsets[j]), float(outside[j] / masked[k])
    else:
        next_offset, next_ratio = float("nan"), 0.0
    r = _pearson_at(logger_time, logger_values, machine_time, machine_values, offset, step_s)
    return float(offset), r, next_ratio, next_offset


def _pearson_at(logger_time, logger_values, machine_time, machine_values, offset, step_s) -> float:
    start = max(machine_time[0], logger_time[0] - offset)
    stop = min(machine_time[-1], logger_time[-1] - offset)
    if stop - start < 3 * step_s:
        return float("nan")
    t = np.arange(start, stop, step_s)
    x = np.interp(t + offset, logger_time, logger_values)
    y = np.interp(t, machine_time, machine_values)
    if x.std() == 0 or y.std() == 0:
        return float("nan")
    return float(np.corrcoef(x, y)[0, 1])


def align(
    logger: dict[str, np.ndarray],
    machine: dict[str, np.ndarray],
    logger_signal: str = "gauge_pressure_Pa",
    machine_signal: str = "extension_m",
    max_offset_s: float | None = None,
) -> Alignment:
    """Finds the offset between a logger file and a machine export (see :func:`find_offset`).

    The default pairs pressure with extension: in a sealed muscle the pressure follows the volume,
    a function of the length, without lag; the load also carries friction and bladder hysteresis,
    which shift its peaks against the pressure's (by 0.1 s in a simulated thesis test)."""
    if logger_signal not in logger:
        raise LoggerError(f"the logger file has no {logger_signal} column (has: {', '.join(logger)})")
    if machine_signal not in machine:
        raise LoggerError(f"the machine export has no {machine_signal} (has: {', '.join(machine)})")
    step = float(np.median(np.diff(logger["time_s"])))
    offset, r, next_ratio, next_offset = find_offset(
        logger["time_s"], logger[logger_signal], machine["time_s"], machine[machine_signal], step, max_offset_s
    )
    return Alignment(offset, r, next_ratio, next_offset, step, logger_signal, machine_signal)


# --- the muscle tested --------------------------------------------------------------------------


def read_muscle_source(path: str | Path) -> dict[str, dict]:
    """The [muscle] table (and [friction], [gas] if present) of a TOML file: an experiment, or a
    file holding only the muscle (its keys at the top level or under [muscle])."""
    path = Path(path)
    try:
        with path.open("rb") as handle:
            document = tomllib.load(handle)
    except FileNotFoundError:
        raise LoggerError(f"{path}: no such muscle file") from None
    except tomllib.TOMLDecodeError as error:
        raise LoggerError(f"{path}: not valid TOML: {error}") from None
    if "muscle" in document:
        return {section: document[section] for section in ("muscle", "friction", "gas") if section in document}
    if all(not isinstance(value, dict) for value in document.values()) and document:
        return {"muscle": document}
    raise LoggerError(f"{path}: no [muscle] section and no muscle keys at the top level")
