"""A discovered term, kept: the equation discovery found (discover.py) as a `pamkit.Effect` that
adds its terms to their channel's reading, saved to and loaded from a small JSON file so that
the next run can use it (`--effect`)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

import pamkit
from pamkit.diagnosis.cycles import find_cycles
from pamkit.diagnosis.discover import _equation
from pamkit.diagnosis.features import MOTION_TERMS, DiscoveryError, _feature_columns

FORMAT = "pamkit.discovered_effect"
# 2: channels and the record's inputs in SI (gauge_pressure_Pa, temperature_K; ambient_K).
FORMAT_VERSION = 2

CHANNELS = tuple(pamkit.measured_channels())  # declared once, in C++ (effect.hpp)
TERM_NAMES = (
    "offset",
    *MOTION_TERMS,
    "x",
    "x^2",
    "x^3",
    "p",
    "dp/dt",
    "sign(dp/dt)",
    "sign(dp/dt)*p",
    "F",
    "F^2",
    "t",
    "cycle",
    "T-T_ambient",
)


def _default_cycle_index(time_s: np.ndarray, elongation_m: np.ndarray) -> np.ndarray:
    return find_cycles(elongation_m).index(elongation_m.size).astype(float)


class DiscoveredEffect(pamkit.Effect):
    """The terms discovery found, added to their channel's reading (stage 3, the instruments'
    readings): ``channel += Σ coefficient · feature``, each feature recomputed from the
    measurement's time, elongation, pressure and temperature with the scales (v0, derivative
    window, deadband, ambient) of the record it was fitted on. Its parameters are the
    coefficients, c0, c1, ... in the order of ``terms``."""

    def __init__(self, result: dict, name: str | None = None, cycle_index=None):
        super().__init__()
        channel = result.get("channel")
        if channel not in CHANNELS:
            raise DiscoveryError(f"discovered effect: channel {channel!r} is not one of {', '.join(CHANNELS)}")
        terms = result.get("terms") or []
        if not terms:
            raise DiscoveryError(
                f"discovered effect: no terms were discovered for {channel} ({result.get('equation', '')})"
            )
        for k, term in enumerate(terms):
            missing = [key for key in ("name", "expression", "coefficient", "unit") if key not in term]
            if missing:
                raise DiscoveryError(f"discovered effect: terms[{k}] lacks {', '.join(missing)}")
            if term["name"] not in TERM_NAMES:
                raise DiscoveryError(
                    f"discovered effect: terms[{k}].name = {term['name']!r} is not a library term "
                    f"({', '.join(TERM_NAMES)})"
                )
            numbers = {"coefficient": term["coefficient"], **term.get("parameters", {})}
            for key, value in numbers.items():
                if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                    raise DiscoveryError(f"discovered effect: terms[{k}].{key} = {value!r} is not a finite number")
        self.channel = channel
        self.terms = [dict(term) for term in terms]
        self.coefficients = [float(term["coefficient"]) for term in terms]
        self._name = name or f"discovered_{channel}"
        self._cycle_index = cycle_index or _default_cycle_index
        self._equation = result.get("equation") or _equation(channel, self.terms)

    def name(self):
        return self._name

    def description(self):
        return f"discovered by sparse regression on the residual: {self._equation}"

    def _bounds(self, k: int) -> tuple[float, float, float, float]:
        """Numeric bounds wide enough for any sign and tenfold the size; the plausible range is
        the fitted 95 % interval (white-noise standard error)."""
        fitted = float(self.terms[k]["coefficient"])
        spread = float(self.terms[k].get("standard_error", 0.0))
        reach = 10.0 * (abs(fitted) + spread)
        return fitted - reach, fitted + reach, fitted - 1.96 * spread, fitted + 1.96 * spread

    def parameters(self):
        return [
            pamkit.EffectParameter(
                f"c{k}",
                self.coefficients[k],
                term["unit"],
                *self._bounds(k),
                f"coefficient of {term['expression']}: {term.get('resembles', '')}",
            )
            for k, term in enumerate(self.terms)
        ]

    def set(self, key, value):
        keys = [f"c{k}" for k in range(len(self.terms))]
        if key not in keys:
            raise ValueError(f"effect {self._name} has no parameter {key!r} ({', '.join(keys)})")
        try:
            number = float(value)
        except ValueError:
            raise ValueError(f"effect {self._name}: {key} = {value!r} is not a number") from None
        low, high = self._bounds(keys.index(key))[:2]
        if not low <= number <= high:
            raise ValueError(f"effect {self._name}: {key} = {number} is outside [{low:g}, {high:g}]")
        self.coefficients[keys.index(key)] = number

    def correction(self, time_s, elongation_m, gauge_pressure_Pa=None, temperature_K=None, force_N=None) -> np.ndarray:
        """Σ coefficient · feature on a record (SI) [the channel's unit]."""
        time_s = np.asarray(time_s, dtype=float)
        elongation_m = np.asarray(elongation_m, dtype=float)
        names = {term["name"] for term in self.terms}
        scales = {key: value for term in self.terms for key, value in term.get("parameters", {}).items()}
        pressure = None if gauge_pressure_Pa is None else np.asarray(gauge_pressure_Pa, dtype=float)
        temperature = None if temperature_K is None else np.asarray(temperature_K, dtype=float)
        force = None if force_N is None else np.asarray(force_N, dtype=float)
        cycle = self._cycle_index(time_s, elongation_m) if "cycle" in names else None
        columns = {
            term.name: values
            for term, values in _feature_columns(
                time_s,
                elongation_m,
                pressure,
                temperature,
                scales.get("ambient_K"),
                cycle,
                force,
                include_motion=bool(names & set(MOTION_TERMS)),
                scales=scales,
            )
        }
        total = np.zeros(time_s.size)
        for term, coefficient in zip(self.terms, self.coefficients):
            if term["name"] not in columns:
                raise DiscoveryError(f"effect {self._name}: {term['expression']} needs a channel this record lacks")
            total += coefficient * columns[term["name"]]
        return total

    def apply_to_measurement(self, measurement):
        # Every feature is read before the channel changes (the force terms read the model's force).
        correction = self.correction(
            measurement.time_s,
            measurement.elongation_m,
            measurement.gauge_pressure_Pa,
            measurement.temperature_K,
            measurement.force_N,
        )
        setattr(measurement, self.channel, getattr(measurement, self.channel) + correction)
        return measurement


def discovered_effect(result: dict, name: str | None = None, cycle_index=None) -> DiscoveredEffect:
    """A pamkit.Effect that adds the discovered terms to their channel, for the next run.

    Args:
        result: discover()'s dict (or load_effect's file contents).
        name: the effect's name; default ``discovered_<channel>``.
        cycle_index: ``f(time_s, elongation_m) -> cycle of every sample``, needed only by a
            ``cycle`` term; default pamkit.diagnosis.cycles.find_cycles.

    Raises:
        DiscoveryError: when nothing was discovered, or a term is not a library term.
    """
    return DiscoveredEffect(result, name, cycle_index)


def save_effect(result: dict, path: str | Path) -> None:
    """Writes the discovered terms as a small JSON file that load_effect reads back."""
    discovered_effect(result)  # refuse to write what could not be loaded
    document = {
        "format": FORMAT,
        "version": FORMAT_VERSION,
        "channel": result["channel"],
        "channel_unit": result.get("channel_unit", ""),
        "equation": result["equation"],
        "gain": result.get("gain", {}),
        "gain_ci95": result.get("gain_ci95", {}),
        "terms": [
            {
                key: term[key]
                for key in ("name", "expression", "coefficient", "unit", "resembles", "standard_error", "parameters")
                if key in term
            }
            for term in result["terms"]
        ],
    }
    Path(path).write_text(json.dumps(document, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")


def load_effect(path: str | Path, name: str | None = None, cycle_index=None) -> DiscoveredEffect:
    """The effect save_effect wrote.

    Raises:
        DiscoveryError: naming the file and what is wrong (missing, not JSON with the line, not
            a discovered effect, a bad term).
    """
    path = Path(path)
    try:
        document = json.loads(path.read_text(encoding="utf-8"))
    except OSError as error:
        raise DiscoveryError(f"{path}: cannot read the discovered effect ({error.strerror})") from None
    except json.JSONDecodeError as error:
        raise DiscoveryError(f"{path}:{error.lineno}: not JSON ({error.msg})") from None
    if not isinstance(document, dict) or document.get("format") != FORMAT:
        raise DiscoveryError(f"{path}: not a discovered effect (format should be {FORMAT!r})")
    if document.get("version") != FORMAT_VERSION:
        raise DiscoveryError(f"{path}: version {document.get('version')!r}; this pamkit reads version {FORMAT_VERSION}")
    try:
        return discovered_effect(document, name, cycle_index)
    except DiscoveryError as error:
        raise DiscoveryError(f"{path}: {error}") from None
