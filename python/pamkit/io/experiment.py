"""Measured (or planned) experiments: a TOML file describing the muscle and the test, naming a
CSV of what was measured (DESIGN.md, "A measured dataset").

Every problem is reported as an :class:`ExperimentError` (a ``ValueError``) that names the
file, and for CSV data the line and column.
"""

from __future__ import annotations

import csv
import io
import json
import math
import numbers
import os
import re
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

try:
    import tomllib
except ModuleNotFoundError:  # Python < 3.11
    import tomli as tomllib

from pamkit._core import (
    BladderLaw,
    Construction,
    FrictionParams,
    GasParams,
    GasProcess,
    MuscleBuild,
    deflated_braid_angle_deg,
    fiber_revolutions_for_braid_angle,
    measured_channels,
)
from pamkit.units import KELVIN_AT_ZERO_CELSIUS

# The columns of a measured time series (DESIGN.md): the time base and the crosshead's motion are
# required; the channels the instruments read (declared once, in C++: effect.hpp's
# measured_channels) are optional. Every module that lists them imports them from here.
REQUIRED_COLUMNS = ("time_s", "elongation_m")
OPTIONAL_COLUMNS = tuple(measured_channels())
SERIES_COLUMNS = REQUIRED_COLUMNS + OPTIONAL_COLUMNS
# The channels the Arduino logger records (the 61CP transducer on A0, the TMP36 on A1); the
# tensile machine records the others.
LOGGER_CHANNELS = ("pressure_kPa", "temperature_C")
GAS_MODES = ("sealed", "supplied")

# Experiment kinds (DESIGN.md, "Experiment kinds"): a time series, or a static table of settled
# rows whose columns are all required.
SERIES_KIND = "series"
TABLE_COLUMNS = {
    "isometric_map": ("length_m", "pressure_kPa", "force_N"),
    "free_inflation": ("pressure_kPa", "length_m", "diameter_m"),
    "isotonic": ("pressure_kPa", "length_m"),  # or contraction_m from the deflated length; time_s optional
}
KINDS = (SERIES_KIND, *TABLE_COLUMNS)

# [test] keys, their meaning, and whether a time series needs them (a static table does not).
TEST_KEYS = {
    "inflation_pressure_kPa": (True, "gauge pressure after inflation, before the first stretch [kPa]"),
    "ambient_temperature_C": (True, "ambient temperature, the gas's initial temperature [°C]"),
    "data": (True, "CSV file, relative to the TOML file"),
    "kind": (False, f"{' or '.join(repr(k) for k in KINDS)} (default {SERIES_KIND!r})"),
    "gas": (False, '"sealed" (default) or "supplied"'),
    "initial_length_m": (False, "muscle length at zero elongation [m]"),
    "load_N": (False, "isotonic: the constant load the muscle carries [N] (or unknown in [calibrate])"),
    "load_mass_kg": (False, "isotonic time series: the hanging load's mass [kg]; the length follows its motion"),
    "description": (False, "free text: where the test comes from"),
    "zero": (False, "a run with no air (CSV, relative to the TOML): its means zero the load cell and transducer"),
    "preload_N": (False, "supplied: the force the deflated muscle was mounted with; sets its length [N]"),
    "force_range_N": (False, "[lowest, highest] force the load cell reads; it clips beyond [N]"),
    "pressure_range_kPa": (False, "[lowest, highest] gauge pressure the transducer reads; it clips beyond [kPa]"),
    "specimen": (False, "a tensile machine's export of several specimens: the one this test is (its Specimen Number)"),
}
# [test] ranges of the instruments, by the channel they read.
RANGE_KEYS = {"force_N": "force_range_N", "pressure_kPa": "pressure_range_kPa"}
TABLE_DEFAULTS = {"inflation_pressure_kPa": 0.0, "ambient_temperature_C": 20.0}
# [gas] keys beyond GasParams' fields: the process by name.
GAS_PROCESS_KEY = "process"
# [muscle] key beyond MuscleBuild's fields: what a datasheet gives instead of fiber_revolutions.
BRAID_ANGLE_KEY = "braid_angle_deg"
# [muscle] key beyond MuscleBuild's fields: how fibres and membrane are put together, by name.
CONSTRUCTION_KEY = "construction"
# [muscle] dimensions that scale with the braid diameter when a file leaves them out.
SCALED_WITH_DIAMETER = (
    "bladder_diameter_m",
    "bladder_thickness_m",
    "fiber_thickness_m",
    "end_diameter_m",
    "cone_generator_m",
)
# The sections of an experiment file.
EXPERIMENT_SECTIONS = ("muscle", "bladder", "friction", "gas", "calibrate", "test")
# The sections a campaign file shares with its tests, besides [campaign] itself.
CAMPAIGN_SECTIONS = ("campaign", "muscle", "bladder", "friction", "gas", "calibrate")
# [bladder] keys: the law by name, and the neo-Hookean modulus.
BLADDER_LAWS = ("thesis", "neo_hookean", "none")


class ExperimentError(ValueError):
    """An experiment file or its data cannot be used; the message says where."""


class ExperimentWarning(UserWarning):
    """Data that can be used after a stated repair (a cut last line dropped, repeated time stamps
    merged); the message says where and what was done."""


@dataclass
class Experiment:
    """One experiment: the muscle, the test conditions and the measured series (SI units,
    except where a name carries its unit)."""

    path: Path
    build: MuscleBuild
    inflation_pressure_kPa: float
    ambient_temperature_C: float
    data_path: Path
    gas: str = "sealed"
    initial_length_m: float | None = None
    description: str = ""
    friction: FrictionParams = field(default_factory=FrictionParams)
    gas_params: GasParams = field(default_factory=GasParams)
    bladder: BladderLaw = field(default_factory=BladderLaw.thesis)
    kind: str = SERIES_KIND
    calibrate: dict[str, tuple[float, float]] = field(default_factory=dict)
    load_N: float | None = None
    load_mass_kg: float | None = None
    zeroed: dict[str, float] = field(default_factory=dict)  # offsets the zero run took off each channel
    preload_N: float | None = None
    ranges: dict[str, tuple[float, float]] = field(default_factory=dict)  # what each instrument reads
    columns: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def is_table(self) -> bool:
        """A static table of settled rows, not a time series."""
        return self.kind in TABLE_COLUMNS

    @property
    def time_s(self) -> np.ndarray:
        return self.columns["time_s"]

    @property
    def elongation_m(self) -> np.ndarray:
        return self.columns["elongation_m"]

    def measured(self) -> list[str]:
        """The optional channels present in the data."""
        return [name for name in OPTIONAL_COLUMNS if name in self.columns]

    def reading_range(self, channel: str) -> tuple[float, float]:
        """The declared range of the channel's instrument, in the data's units: shifted by what the
        zero run took off (the instrument clips its raw reading)."""
        lowest, highest = self.ranges.get(channel, (-math.inf, math.inf))
        offset = self.zeroed.get(channel, 0.0)
        return lowest - offset, highest - offset

    def read(self, channel: str, values: np.ndarray) -> np.ndarray:
        """What the channel's instrument reads of true `values`: clipped into its range."""
        return np.clip(values, *self.reading_range(channel)) if channel in self.ranges else values

    @property
    def censored(self) -> np.ndarray:
        """Rows whose supplied pressure reads at an end of the transducer's range: the pressure
        that drove the muscle there is unknown (a reading of 0 kPa may be any pressure below the
        transducer's offset), so they are predicted but never fitted or scored."""
        rows = len(next(iter(self.columns.values())))
        if self.gas != "supplied" or "pressure_kPa" not in self.ranges:
            return np.zeros(rows, dtype=bool)
        lowest, highest = self.reading_range("pressure_kPa")
        return (self.columns["pressure_kPa"] <= lowest) | (self.columns["pressure_kPa"] >= highest)


def _fail(path: Path, message: str) -> ExperimentError:
    return ExperimentError(f"{path}: {message}")


def _number(path: Path, section: str, key: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise _fail(path, f"[{section}] {key} = {value!r} must be a number")
    if not math.isfinite(value):
        raise _fail(path, f"[{section}] {key} = {value!r} must be finite")
    return float(value)


def _fill_struct(path: Path, section: str, table: dict, struct, extra_keys=()):
    """Sets the fields of a bound parameter struct from a TOML table, by the struct's own field
    list, rejecting unknown keys and validating the result."""
    fields = type(struct).fields()
    for key, value in table.items():
        if key in extra_keys:
            continue
        if key not in fields:
            known = ", ".join(sorted(list(fields) + list(extra_keys)))
            raise _fail(path, f"unknown key [{section}] {key} (known: {known})")
        setattr(struct, key, _number(path, section, key, value))
    try:
        struct.validate()
    except ValueError as error:
        raise _fail(path, f"[{section}] {error}") from None
    return struct


def _scaled_defaults(path: Path, table: dict) -> MuscleBuild:
    """The defaults of the dimensions a file leaves out, scaled with its braid diameter: PAM 2's
    (table C.4) are for a 20 mm braid, and a 10 mm muscle declared by its datasheet (length and
    diameter) would otherwise get a bladder and end caps wider than its braid."""
    build = MuscleBuild()
    if "diameter_m" not in table:
        return build
    scale = _number(path, "muscle", "diameter_m", table["diameter_m"]) / build.diameter_m
    for name in SCALED_WITH_DIAMETER:
        if name not in table:
            setattr(build, name, scale * getattr(build, name))
    return build


def _read_build(path: Path, table: dict) -> MuscleBuild:
    """[muscle]: MuscleBuild's fields, or braid_angle_deg instead of fiber_revolutions, and the
    construction by name ("sleeve", the default, or "embedded")."""
    table = dict(table)
    angle = table.pop(BRAID_ANGLE_KEY, None)
    if angle is not None and "fiber_revolutions" in table:
        raise _fail(path, f"[muscle] gives both {BRAID_ANGLE_KEY} and fiber_revolutions: give one, they say the same")
    construction = table.pop(CONSTRUCTION_KEY, "sleeve")
    if construction not in Construction.__members__:
        raise _fail(
            path, f"[muscle] {CONSTRUCTION_KEY} = {construction!r} must be one of {', '.join(Construction.__members__)}"
        )
    build = _scaled_defaults(path, table)
    build.construction = Construction.__members__[construction]
    if angle is None:
        return _fill_struct(path, "muscle", table, build)
    angle = _number(path, "muscle", BRAID_ANGLE_KEY, angle)
    for key, value in table.items():  # the angle converts through the other dimensions
        if key in type(build).fields():
            setattr(build, key, _number(path, "muscle", key, value))
    try:
        build.fiber_revolutions = fiber_revolutions_for_braid_angle(build, angle)
    except ValueError as error:
        raise _fail(path, f"[muscle] {error}") from None
    return _fill_struct(path, "muscle", table, build)


def _read_bladder(path: Path, table: dict) -> BladderLaw:
    """[bladder]: law = "thesis" (default), "neo_hookean" (with shear_modulus_Pa) or "none"."""
    known = {"law", "shear_modulus_Pa"}
    for key in table:
        if key not in known:
            raise _fail(path, f"unknown key [bladder] {key} (known: {', '.join(sorted(known))})")
    law = table.get("law", "thesis")
    if law not in BLADDER_LAWS:
        raise _fail(path, f"[bladder] law = {law!r} must be one of {', '.join(BLADDER_LAWS)}")
    if law == "neo_hookean":
        if "shear_modulus_Pa" not in table:
            raise _fail(path, "[bladder] law = 'neo_hookean' needs shear_modulus_Pa (rubbers: 0.2e6-3e6 Pa)")
        try:
            return BladderLaw.neo_hookean(_number(path, "bladder", "shear_modulus_Pa", table["shear_modulus_Pa"]))
        except ValueError as error:
            raise _fail(path, f"[bladder] {error}") from None
    if "shear_modulus_Pa" in table:
        raise _fail(path, f"[bladder] shear_modulus_Pa belongs to law = 'neo_hookean', not {law!r}")
    return BladderLaw.thesis() if law == "thesis" else BladderLaw.none()


def calibratable_fields() -> dict[str, tuple[float, float, str]]:
    """What [calibrate] may name: each field with its allowed range and unit."""
    fields = {name: (info["min"], info["max"], info["unit"]) for name, info in MuscleBuild.fields().items()}
    fields[BRAID_ANGLE_KEY] = (1.0, 89.0, "deg")
    fields["load_N"] = (0.0, 1e5, "N")
    fields["bladder.shear_modulus_Pa"] = (0.0, 1e9, "Pa")
    return fields


def declared_value(name: str, build: MuscleBuild, bladder: BladderLaw, load_N: float | None = None) -> float:
    """The value an experiment file declares for a [calibrate] name (NaN for a load it leaves out)."""
    if name == "load_N":
        return load_N if load_N is not None else math.nan
    if name == BRAID_ANGLE_KEY:
        return deflated_braid_angle_deg(build)
    if name == "bladder.shear_modulus_Pa":
        return bladder.shear_modulus_Pa
    return getattr(build, name)


def _read_calibrate(path: Path, table: dict, bladder: BladderLaw) -> dict[str, tuple[float, float]]:
    """[calibrate]: fields not known, each with [lower, upper] bounds within its allowed range."""
    flat: dict[str, object] = {}
    for key, value in table.items():
        if isinstance(value, dict):  # [calibrate.bladder] or bladder.shear_modulus_Pa = [...]
            flat.update({f"{key}.{inner}": bounds for inner, bounds in value.items()})
        else:
            flat[key] = value
    allowed = calibratable_fields()
    out = {}
    for name, bounds in flat.items():
        if name not in allowed:
            raise _fail(path, f"[calibrate] {name}: not a field pamkit can calibrate (known: {', '.join(allowed)})")
        if (
            not isinstance(bounds, list)
            or len(bounds) != 2
            or not all(isinstance(b, (int, float)) and not isinstance(b, bool) for b in bounds)
        ):
            raise _fail(path, f"[calibrate] {name} = {bounds!r} must be [lower, upper]")
        lower, upper = float(bounds[0]), float(bounds[1])
        low, high, unit = allowed[name]
        if not (math.isfinite(lower) and math.isfinite(upper) and lower < upper):
            raise _fail(path, f"[calibrate] {name} = [{lower}, {upper}] needs finite lower < upper")
        if lower < low or upper > high:
            raise _fail(path, f"[calibrate] {name} = [{lower}, {upper}] {unit} leaves the allowed [{low}, {high}]")
        if name == "bladder.shear_modulus_Pa" and bladder.form != BladderLaw.Form.neo_hookean:
            raise _fail(path, "[calibrate] bladder.shear_modulus_Pa needs [bladder] law = 'neo_hookean'")
        if name == "fiber_revolutions" and BRAID_ANGLE_KEY in flat:
            raise _fail(path, f"[calibrate] names both fiber_revolutions and {BRAID_ANGLE_KEY}: they are one unknown")
        out[name] = (lower, upper)
    return out


def _range(path: Path, key: str, value) -> tuple[float, float]:
    """An instrument's [lowest, highest] reading."""
    if not isinstance(value, list) or len(value) != 2:
        raise _fail(path, f"[test] {key} = {value!r} must be [lowest, highest]")
    lowest, highest = (_number(path, "test", key, v) for v in value)
    if not lowest < highest:
        raise _fail(path, f"[test] {key} = [{lowest}, {highest}] needs lowest < highest")
    return lowest, highest


def _named_file(path: Path, key: str, name) -> Path:
    """The absolute path of a file the experiment names in [test] `key`, relative to its TOML.

    Raises:
        ExperimentError: for a name that is not a string or holds a control character: a NUL no
            file system takes (os calls raise a bare ValueError), a line end that would split
            every message naming the file.
    """
    if not isinstance(name, str):
        raise _fail(path, f"[test] {key} = {name!r} must be a file name")
    if any(ord(character) < 0x20 or ord(character) == 0x7F for character in name):
        raise _fail(path, f"[test] {key} = {name!r} holds a control character: not a file name")
    try:
        return (path.parent / name).resolve()
    except (RuntimeError, OSError):
        # A symbolic link loop (RuntimeError before Python 3.13, OSError since): keep the path
        # as written, and let reading it say what it is.
        return Path(os.path.abspath(path.parent / name))


def _document(path: Path) -> dict:
    try:
        return tomllib.loads(_text(path, "experiment"))
    except tomllib.TOMLDecodeError as error:
        raise _fail(path, f"not valid TOML: {error}") from None


def load_tests(path: str | Path) -> list[Experiment]:
    """The experiments a TOML names: itself, or a campaign's tests (`[campaign] tests = [...]`,
    paths relative to it), each with the campaign's `[muscle]`, `[bladder]`, `[friction]`,
    `[gas]` and `[calibrate]` sections (DESIGN.md, "Campaigns"); a test may not give a section
    the campaign gives.

    Raises:
        ExperimentError: naming the campaign file, or the test's file, of the first problem.
    """
    path = Path(path)
    document = _document(path)
    if "campaign" not in document:
        return [load_experiment(path)]
    for section in document:
        if section not in CAMPAIGN_SECTIONS:
            raise _fail(path, f"unknown section [{section}] in a campaign (known: {', '.join(CAMPAIGN_SECTIONS)})")
    campaign = document.pop("campaign")
    for key in campaign:
        if key != "tests":
            raise _fail(path, f"unknown key [campaign] {key} (known: tests)")
    tests = campaign.get("tests")
    if not isinstance(tests, list) or not tests or not all(isinstance(t, str) for t in tests):
        raise _fail(path, f"[campaign] tests = {tests!r} must be a list of experiment files")
    return [load_experiment(path.parent / test, shared=document) for test in tests]


def load_experiment(path: str | Path, shared: dict | None = None) -> Experiment:
    """Reads an experiment TOML and its CSV (pamkit's own, a spreadsheet's with ";" and decimal
    commas, or a tensile machine's export: Instron Bluehill, ZwickRoell testXpert); `shared`
    sections (a campaign's) are added to it.

    Returns:
        An :class:`Experiment`: the muscle (``build``, SI units), the test conditions
        (``inflation_pressure_kPa`` gauge, ``ambient_temperature_C``, ``gas``) and ``columns``,
        a dict of 1-D float arrays of one length N (rows of the CSV), units in their names:
        time_s [s], elongation_m [m], and as measured force_N [N], pressure_kPa [kPa, gauge],
        temperature_C [°C]; a static table has its own (length_m [m], diameter_m [m], ...).

    Raises:
        ExperimentError: naming the file (and line and column for CSV data) of the first problem.
    """
    path = Path(path)
    document = _document(path)
    if "campaign" in document:
        raise _fail(path, "a campaign file, not one experiment: diagnose it, or load its tests with load_tests")
    for section, table in (shared or {}).items():
        if section in document:
            raise _fail(path, f"gives [{section}], which its campaign shares: give it in one place")
        document[section] = table

    for section in document:
        if section not in EXPERIMENT_SECTIONS:
            raise _fail(path, f"unknown section [{section}] (known: {', '.join(sorted(EXPERIMENT_SECTIONS))})")
    for section in ("muscle", "test"):
        if section not in document:
            raise _fail(path, f"missing section [{section}]")
    for section, table in document.items():
        if not isinstance(table, dict):
            raise _fail(path, f"{section} = {table!r}: [{section}] is a section (a [{section}] line, then its keys)")

    build = _read_build(path, document["muscle"])
    bladder = _read_bladder(path, document.get("bladder", {}))
    friction = _fill_struct(path, "friction", document.get("friction", {}), FrictionParams())
    gas_table = document.get("gas", {})
    gas_params = GasParams()
    if GAS_PROCESS_KEY in gas_table:
        name = gas_table[GAS_PROCESS_KEY]
        if not isinstance(name, str) or name not in GasProcess.__members__:  # a list is no dict key
            raise _fail(path, f"[gas] process = {name!r} must be one of {', '.join(GasProcess.__members__)}")
        gas_params.process = GasProcess.__members__[name]
    _fill_struct(path, "gas", gas_table, gas_params, extra_keys=(GAS_PROCESS_KEY,))

    test = dict(document["test"])
    for key in test:
        if key not in TEST_KEYS:
            raise _fail(path, f"unknown key [test] {key} (known: {', '.join(TEST_KEYS)})")
    kind = test.get("kind", SERIES_KIND)
    if kind not in KINDS:
        raise _fail(path, f"[test] kind = {kind!r} must be one of {', '.join(KINDS)}")
    if kind in TABLE_COLUMNS and "zero" in test:
        raise _fail(
            path, f"[test] zero: a {kind} table is zeroed before it is tabulated; zero runs apply to time series"
        )
    if kind in TABLE_COLUMNS:
        # A table of settled rows at supplied pressures: no inflation to seal, no gas to warm.
        for key, default in TABLE_DEFAULTS.items():
            test.setdefault(key, default)
        if test.get("gas", "supplied") != "supplied":
            raise _fail(path, f"[test] gas = {test['gas']!r}: a {kind} table is measured at supplied pressures")
        test["gas"] = "supplied"
    for key, (required, meaning) in TEST_KEYS.items():
        if required and key not in test:
            raise _fail(path, f"missing key [test] {key} ({meaning})")
    pressure = _number(path, "test", "inflation_pressure_kPa", test["inflation_pressure_kPa"])
    if pressure < 0 or pressure > 2000:
        raise _fail(path, f"[test] inflation_pressure_kPa = {pressure} is outside [0, 2000] kPa (gauge)")
    ambient = _number(path, "test", "ambient_temperature_C", test["ambient_temperature_C"])
    if ambient < -50 or ambient > 150:
        raise _fail(path, f"[test] ambient_temperature_C = {ambient} is outside [-50, 150] °C")
    gas_params.ambient_temperature_K = ambient + KELVIN_AT_ZERO_CELSIUS
    gas = test.get("gas", "sealed")
    if gas not in GAS_MODES:
        raise _fail(path, f"[test] gas = {gas!r} must be one of {', '.join(GAS_MODES)}")
    initial_length = test.get("initial_length_m")
    if initial_length is not None:
        initial_length = _number(path, "test", "initial_length_m", initial_length)
        if not 0 < initial_length <= 5:
            raise _fail(path, f"[test] initial_length_m = {initial_length} is outside (0, 5] m")
    calibrate = _read_calibrate(path, document.get("calibrate", {}), bladder)
    load = test.get("load_N")
    if load is not None:
        load = _number(path, "test", "load_N", load)
        if kind != "isotonic":
            raise _fail(path, f'[test] load_N belongs to kind = "isotonic", not {kind!r}')
        if not 0 <= load <= 1e5:
            raise _fail(path, f"[test] load_N = {load} is outside [0, 1e5] N")
    elif kind == "isotonic" and "load_N" not in calibrate:
        raise _fail(path, "[test] load_N is missing: an isotonic test needs its load, or load_N in [calibrate]")
    mass = test.get("load_mass_kg")
    if mass is not None:
        mass = _number(path, "test", "load_mass_kg", mass)
        if kind != "isotonic":
            raise _fail(path, f'[test] load_mass_kg belongs to kind = "isotonic", not {kind!r}')
        if not 0 < mass <= 1e4:
            raise _fail(path, f"[test] load_mass_kg = {mass} is outside (0, 1e4] kg")
    if "load_N" in calibrate and kind != "isotonic":
        raise _fail(path, f'[calibrate] load_N belongs to kind = "isotonic", not {kind!r}')
    preload = test.get("preload_N")
    if preload is not None:
        preload = _number(path, "test", "preload_N", preload)
        if gas != "supplied" or kind != SERIES_KIND:
            raise _fail(path, "[test] preload_N belongs to a supplied time series: a rig that holds the mounted length")
        if initial_length is not None:
            raise _fail(path, "[test] gives both preload_N and initial_length_m: the preload sets the length")
        if not 0 < preload <= 1e5:
            raise _fail(path, f"[test] preload_N = {preload} is outside (0, 1e5] N")
    ranges = {channel: _range(path, key, test[key]) for channel, key in RANGE_KEYS.items() if key in test}
    data_path = _named_file(path, "data", test["data"])

    experiment = Experiment(
        path=path,
        build=build,
        inflation_pressure_kPa=pressure,
        ambient_temperature_C=ambient,
        data_path=data_path,
        gas=gas,
        initial_length_m=initial_length,
        description=str(test.get("description", "")),
        friction=friction,
        gas_params=gas_params,
        bladder=bladder,
        kind=kind,
        calibrate=calibrate,
        load_N=load,
        preload_N=preload,
        ranges=ranges,
        load_mass_kg=mass,
    )
    if kind != SERIES_KIND and "specimen" in test:
        raise _fail(path, f"[test] specimen chooses among a tensile machine's specimens: a {kind} table has none")
    if kind == "isotonic":
        experiment.columns = _read_isotonic(data_path, build, dynamic=mass is not None)
        return experiment
    if kind in TABLE_COLUMNS:
        experiment.columns = read_table(data_path, TABLE_COLUMNS[kind])
        return experiment
    specimen = test.get("specimen")
    if specimen is not None and (isinstance(specimen, bool) or not isinstance(specimen, (str, int))):
        raise _fail(path, f"[test] specimen = {specimen!r} must be a specimen's label (its Specimen Number)")
    experiment.columns = read_series(data_path, None if specimen is None else str(specimen))
    if "zero" in test:
        _zero(experiment, path, test["zero"])
    if gas == "supplied" and "pressure_kPa" not in experiment.columns:
        raise _fail(data_path, 'a "supplied" test drives the model with pressure_kPa: the column is missing')
    return experiment


def read_series(path: str | Path, specimen: str | None = None) -> dict[str, np.ndarray]:
    """Reads a measured-data CSV: a header row, then numbers. Requires time_s and elongation_m,
    accepts force_N, pressure_kPa, temperature_C; time must increase.

    A tensile machine's export (Instron Bluehill, ZwickRoell testXpert: pamkit.io.machine) is
    recognised by its header and read as time_s, elongation_m (the crosshead's extension, which
    the machine zeroes at the start of the test) and force_N, converted from its units row; of an
    export of several specimens, `specimen` (its label) is read.

    Raises:
        ExperimentError: naming the file, line and column of the first bad value; for a
            `specimen` asked of a file that is not a machine's export.
    """
    path = Path(path)
    if _is_machine_export(path):
        from pamkit.io.machine import read_machine_export  # it builds on this module

        columns = read_machine_export(path, specimen).columns
        return {"time_s": columns["time_s"], "elongation_m": columns["extension_m"], "force_N": columns["force_N"]}
    if specimen is not None:
        raise ExperimentError(
            f"{path}: [test] specimen = {specimen!r} chooses among a tensile machine's specimens; this is pamkit's CSV "
            "of one test: leave it out"
        )
    return _read_csv(path, REQUIRED_COLUMNS, OPTIONAL_COLUMNS, increasing="time_s")


def _is_machine_export(path: Path) -> bool:
    """Whether a data file is a tensile machine's export rather than pamkit's CSV: its first line
    names none of pamkit's channels, and a machine's names row follows. ("time_s,elongation_m,
    force_kN" is pamkit's CSV with a wrong name, not an export with units in its names.) A file
    that cannot be opened is left to _read_csv, which says why."""
    from pamkit.io.machine import looks_like_export

    try:
        if not path.is_file():
            return False
        with path.open("rb") as handle:
            first_line = _first_line(handle.readline(MAX_LINE_BYTES).decode("utf-8-sig", errors="replace"))
        names = [name.strip() for name in next(csv.reader([first_line], delimiter=_delimiter(first_line)), [])]
        if any(name in REQUIRED_COLUMNS + OPTIONAL_COLUMNS for name in names):
            return False  # pamkit's CSV, right or wrong: its errors name what to fix, no column is dropped
        return looks_like_export(path)
    except OSError:
        return False


ZEROED_CHANNELS = ("force_N", "pressure_kPa")  # not temperature: with no air, the TMP36 reads the room


def _zero(experiment: Experiment, path: Path, name) -> None:
    """Takes the means of a run with no air (the rig's offset run) off the load cell's and the
    transducer's channels, as a lab zeroes its sensors; records what it took. The offset run of
    a preloaded mount is recorded on the mounted muscle: its force holds the preload, which is
    the muscle's, not the cell's, and stays in the data."""
    run = read_series(_named_file(path, "zero", name))
    shared = [c for c in ZEROED_CHANNELS if c in run and c in experiment.columns]
    if not shared:
        raise _fail(
            path, f"[test] zero = {name!r} has none of the channels it could zero ({', '.join(ZEROED_CHANNELS)})"
        )
    for channel in shared:
        offset = float(np.mean(run[channel]))
        if channel == "force_N" and experiment.preload_N is not None:
            offset -= experiment.preload_N
        experiment.columns[channel] = experiment.columns[channel] - offset
        experiment.zeroed[channel] = offset


def _read_isotonic(path: Path, build: MuscleBuild, dynamic: bool = False) -> dict[str, np.ndarray]:
    """An isotonic test's rows: pressure_kPa and the muscle's length_m, or its contraction_m
    from the deflated length (converted to length_m); time_s when there is one, and always,
    increasing, for a `dynamic` test (a load whose motion is integrated in time)."""
    header = _header(path)
    measures = [name for name in ("length_m", "contraction_m") if name in header]
    if len(measures) != 1:
        raise ExperimentError(
            f"{path}:1: an isotonic test gives its length as one of length_m or contraction_m; found "
            f"{', '.join(measures) or 'neither'}"
        )
    if dynamic and "time_s" not in header:
        raise ExperimentError(f"{path}:1: [test] load_mass_kg integrates the load's motion in time: time_s is missing")
    columns = _read_csv(
        path,
        ("pressure_kPa", measures[0]),
        tuple(c for c in ("time_s",) if c in header),
        increasing="time_s" if dynamic else None,
    )
    if "contraction_m" in columns:
        columns["length_m"] = build.length_m - columns.pop("contraction_m")
    return columns


def _header(path: Path) -> list[str]:
    first_line = _first_line(_text(path, "data"))
    return [name.strip() for name in next(csv.reader([first_line], delimiter=_delimiter(first_line)), [])]


def _first_line(text: str) -> str:
    """The text up to its first line end: LF, CR LF or a bare CR (an old Mac's or a logger's line
    end, which the csv module refuses inside a line)."""
    return re.split(r"[\r\n]", text, maxsplit=1)[0]


def _delimiter(first_line: str) -> str:
    """The CSV's delimiter, from its header: European spreadsheets write "time_s;force_N" (and
    decimal commas), some machines tabs."""
    if ";" in first_line and "," not in first_line:
        return ";"
    return "\t" if "\t" in first_line else ","


def read_table(path: str | Path, columns: tuple[str, ...]) -> dict[str, np.ndarray]:
    """Reads a static table (one settled row per line): exactly `columns`, in any order.

    Raises:
        ExperimentError: naming the file, line and column of the first bad value.
    """
    return _read_csv(Path(path), columns, (), increasing=None)


def _read_csv(
    path: Path, required: tuple[str, ...], optional: tuple[str, ...], increasing: str | None
) -> dict[str, np.ndarray]:
    """The columns of a CSV: `required` ones and any of `optional`, `increasing` (if given) not
    decreasing, rows repeating it merged. A plain file is read in blocks by numpy; any other, or
    one with an error to name, row by row with the csv module."""
    columns = _read_plain_csv(path, required, optional, increasing)
    if columns is not None:
        return columns
    text = _text(path, "data")
    header_end = text.find("\n")
    delimiter = _delimiter(text[:header_end] if header_end >= 0 else text)
    decimal_comma = delimiter != ","
    # Something numpy cannot read as it stands: row by row, to name the line and column.
    with io.StringIO(text, newline="") as handle:
        reader = csv.reader(handle, delimiter=delimiter)
        try:
            header = _checked_header(path, next(reader), required, optional)
        except StopIteration:
            raise ExperimentError(f"{path}: empty file, expected a header row") from None
        order = header.index(increasing) if increasing else None
        rows = [(reader.line_num, row) for row in reader]
    cut_last_line = _ends_unterminated(path)
    values: list[list[float]] = []
    merged: list[int] = []  # lines whose time stamp repeated the one before
    weight: list[int] = []  # rows averaged into each value row
    for position, (line, row) in enumerate(rows):
        if not row or all(not cell.strip() for cell in row):
            continue
        try:
            parsed = _parse_row(path, line, header, [c.replace(",", ".") for c in row] if decimal_comma else row)
        except ExperimentError as error:
            if cut_last_line and position == len(rows) - 1:
                # A recording cut mid-line (a killed logger, a pulled cable): keep what came whole.
                warnings.warn(f"{path}:{line}: the last line is cut off ({error}); dropped", ExperimentWarning, 2)
                continue
            raise
        if order is not None and values and parsed[order] == values[-1][order]:
            # A repeated stamp (a logger's clock resolution): one sample, the mean of the rows.
            n = weight[-1]
            values[-1] = [(n * old + new) / (n + 1) for old, new in zip(values[-1], parsed)]
            values[-1][order] = parsed[order]  # the mean of equal stamps, kept exact against the next one
            weight[-1] += 1
            merged.append(line)
            continue
        if order is not None and values and parsed[order] < values[-1][order]:
            raise ExperimentError(
                f"{path}:{line}: column {order + 1} ({increasing}) = {parsed[order]} does not increase"
            )
        values.append(parsed)
        weight.append(1)
    if merged:
        warnings.warn(
            f"{path}:{merged[0]}: {len(merged)} row(s) repeat the time stamp before them (first at line {merged[0]}); "
            "each is merged with it into one sample (their mean)",
            ExperimentWarning,
            2,
        )
    if len(values) < 2:
        raise ExperimentError(f"{path}: needs at least 2 data rows, found {len(values)}")
    table = np.asarray(values)
    return {name: table[:, index].copy() for index, name in enumerate(header)}


def _shown(cell: str, limit: int = 40) -> str:
    """A cell as a message quotes it: on one line (a quoted cell may hold line ends), escaped
    where not printable (a stray byte-order mark), shortened past `limit` characters."""
    return repr(cell if len(cell) <= limit else cell[:limit] + "...")


def _checked_header(path: Path, cells: list[str], required: tuple[str, ...], optional: tuple[str, ...]) -> list[str]:
    """The header's channel names, each known and given once, the required ones all there."""
    header = [name.strip() for name in cells]
    known = required + optional
    for number, name in enumerate(header, start=1):
        if name not in known:
            raise ExperimentError(
                f"{path}:1: column {number} {_shown(name)} is not a known channel ({', '.join(known)})"
            )
        if header.count(name) > 1:
            raise ExperimentError(f"{path}:1: column {_shown(name)} appears twice")
    for name in required:
        if name not in header:
            raise ExperimentError(f"{path}:1: required column '{name}' is missing")
    return header


#: Bytes of a data file numpy parses at a time (then to the end of the line): the file's text
#: never stands in memory whole, only one block of it beside the numbers read so far.
READ_BLOCK_BYTES = 4 << 20


def _read_plain_csv(
    path: Path, required: tuple[str, ...], optional: tuple[str, ...], increasing: str | None
) -> dict[str, np.ndarray] | None:
    """The columns of a plain CSV, read block by block (READ_BLOCK_BYTES) by numpy: a 2-million-row
    file (108 MB) in 80 MB, its numbers, where its bytes, text and numbers at once took 4.5 times
    the file. None when the file is not plain throughout: a quoted cell, a bare carriage return,
    a blank line (numpy skips it, and rows would no longer be lines), a cell numpy does not read
    as a finite number, a row of another width, text that is not UTF-8, a line over
    MAX_LINE_BYTES, no data row, or a file that cannot be opened. The caller then reads its
    whole text row by row, which names the first problem's line and column. A cut last line
    (no line end: a killed logger) is parsed on its own and, as row by row, dropped with a
    warning unless it is a whole row. The header is checked after the rows, as the whole-text
    reader's order of errors has it (a file that cannot be decoded is named as such first)."""
    limit = _checked_size(path, "data")
    try:
        with path.open("rb") as handle:
            first = handle.readline(MAX_LINE_BYTES + 1)
            try:
                header_line = first.decode("utf-8-sig")
            except UnicodeDecodeError:
                return None
            if not header_line.endswith("\n") or not _is_plain(header_line):
                return None
            delimiter = _delimiter(header_line)
            cells = next(csv.reader([header_line[:-1]], delimiter=delimiter))
            # A first pass counts the lines, so that numpy's rows go straight into columns of their
            # final size: the numbers then stand in memory once, not in blocks and again in columns.
            counted = lines = 0
            while block := handle.read(READ_BLOCK_BYTES):
                counted += len(block)
                lines += block.count(b"\n")
                if counted > limit:
                    return None
            if lines * 2 * len(cells) > counted:  # shorter than one character a cell: blank lines
                return None
            handle.seek(len(first))
            columns = [np.empty(lines + 1) for _ in cells]  # and a last line without a line end
            size, rows_read, last = len(first), 0, ""
            while block := handle.read(READ_BLOCK_BYTES):
                if not block.endswith(b"\n"):
                    block += handle.readline(MAX_LINE_BYTES + 1)
                size += len(block)
                if size > limit or _has_long_line(block):
                    return None
                try:
                    text = block.decode("utf-8")
                except UnicodeDecodeError:
                    return None
                if not _is_plain(text):
                    return None
                if not text.endswith("\n"):  # the file's end, without a line end: maybe cut
                    text, _, last = text.rpartition("\n")
                    text = text + "\n" if text else ""
                rows = _parse_block(text, delimiter, len(cells)) if text else np.empty((0, len(cells)))
                if rows is None or rows_read + len(rows) > lines:  # the file grew since it was counted
                    return None
                for index, column in enumerate(columns):
                    column[rows_read : rows_read + len(rows)] = rows[:, index]
                rows_read += len(rows)
    except OSError:
        return None
    if not rows_read:
        return None
    header = _checked_header(path, cells, required, optional)
    if last.strip(delimiter + " \t"):
        line = rows_read + 2
        row = next(csv.reader([last], delimiter=delimiter))
        try:
            values = _parse_row(path, line, header, [c.replace(",", ".") for c in row] if delimiter != "," else row)
        except ExperimentError as error:
            warnings.warn(f"{path}:{line}: the last line is cut off ({error}); dropped", ExperimentWarning, 3)
        else:
            for column, value in zip(columns, values):
                column[rows_read] = value
            rows_read += 1
    for column in columns:
        column.resize(rows_read, refcheck=False)  # in place: nothing else refers to it
    columns = dict(zip(header, columns))
    return _checked_columns(path, columns, 2, increasing)


def _is_plain(text: str) -> bool:
    """No quoted cell (numpy's reader does not unquote), no carriage return but before a line feed."""
    return '"' not in text and text.count("\r") == text.count("\r\n")


def _has_long_line(raw: bytes) -> bool:
    """Whether a line of `raw` (whole lines) is longer than MAX_LINE_BYTES."""
    if len(raw) <= MAX_LINE_BYTES:
        return False
    codes = np.frombuffer(raw, dtype=np.uint8)
    ends = np.concatenate([[-1], np.flatnonzero((codes == ord("\n")) | (codes == ord("\r"))), [len(raw)]])
    return bool((np.diff(ends) - 1 > MAX_LINE_BYTES).any())


def _parse_block(text: str, delimiter: str, width: int) -> np.ndarray | None:
    """Whole lines of numbers parsed by numpy (10^6 rows in about 1.5 s of CPU, where the csv
    module and float() take ten times that): one row a line, `width` finite numbers each, or None."""
    if delimiter != ",":  # decimal commas
        text = text.replace(",", ".")
    try:
        # Bytes, not a StringIO: numpy reads them in chunks, a StringIO would hold 4 bytes a character.
        rows = np.loadtxt(
            io.BytesIO(text.encode()), delimiter=delimiter, dtype=float, ndmin=2, comments=None, encoding="utf-8"
        )
    except ValueError:
        return None
    if rows.shape != (text.count("\n"), width) or not np.isfinite(rows).all():
        return None
    return rows


def _checked_columns(
    path: Path, columns: dict[str, np.ndarray], first_line: int, increasing: str | None
) -> dict[str, np.ndarray]:
    """The columns of rows read at once, with what the row-by-row reader checks and repairs:
    `increasing` must not decrease, and rows repeating its value before them are merged into
    one sample (their mean) with a warning. Row i is on line first_line + i."""
    if increasing is not None:
        stamps = columns[increasing]
        step = np.diff(stamps)
        back = np.flatnonzero(step < 0)
        if back.size:
            row = int(back[0]) + 1
            order = list(columns).index(increasing)
            raise ExperimentError(
                f"{path}:{first_line + row}: column {order + 1} ({increasing}) = {float(stamps[row])} does not increase"
            )
        repeats = np.flatnonzero(step == 0) + 1
        if repeats.size:
            starts = np.flatnonzero(np.concatenate([[True], step != 0]))
            counts = np.diff(np.append(starts, stamps.size))
            columns = {name: np.add.reduceat(column, starts) / counts for name, column in columns.items()}
            first = first_line + int(repeats[0])
            warnings.warn(
                f"{path}:{first}: {repeats.size} row(s) repeat the time stamp before them (first at line {first}); "
                "each is merged with it into one sample (their mean)",
                ExperimentWarning,
                4,
            )
    rows = len(next(iter(columns.values())))
    if rows < 2:
        raise ExperimentError(f"{path}: needs at least 2 data rows, found {rows}")
    return columns


# What a file pamkit reads may hold (issue #14: data = "/dev/zero" once grew to 23 GB). A
# measured row of five channels is about 45 bytes: 10^6 rows, a 17-minute test at 1 kHz, are
# 45 MB, and 256 MiB holds about 6 M rows (1.6 h at 1 kHz). A plain file is read in blocks into
# less memory than its size (its numbers: 8 bytes for ~11 of text); one read row by row (quoted
# cells, blank lines, an error to name) peaks at about 4 bytes of memory per byte of file (its
# bytes, its text, the rows), so the largest file allowed still reads within about 1 GB. An
# experiment TOML is a few kilobytes. No line pamkit writes or reads
# reaches 1 KiB (a header of every channel is 56 bytes); 64 KiB is far beyond any real one and
# below the csv module's 128 KiB cell limit, so an over-long line is named, not a csv error.
MAX_FILE_BYTES = {"experiment": 1 << 20, "data": 256 << 20}
MAX_LINE_BYTES = 64 << 10


def _text(path: Path, what: str, decode=None) -> str:
    """A file's text (UTF-8, a spreadsheet's byte-order mark dropped, or as `decode(raw)` says),
    or an ExperimentError that says why it cannot be read: missing, a folder, not a regular
    file, larger than MAX_FILE_BYTES[what] (its size named), a line over MAX_LINE_BYTES (its
    number named), not UTF-8 (with the line)."""
    limit = _checked_size(path, what)
    try:
        with path.open("rb") as handle:
            raw = handle.read(limit + 1)  # a file that grows while read (or lies about its size) stops here
    except OSError as error:
        raise ExperimentError(f"{path}: cannot be read: {error.strerror}") from None
    if len(raw) > limit:
        raise ExperimentError(f"{path}: more than the {_size(limit)} a {what} file may be")
    _check_line_lengths(path, raw)
    if decode is not None:
        return decode(raw)
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        line = raw[: error.start].count(b"\n") + 1
        raise ExperimentError(f"{path}:{line}: byte 0x{raw[error.start]:02x} is not UTF-8 text") from None


def _checked_size(path: Path, what: str) -> int:
    """MAX_FILE_BYTES[what], once `path` is a regular file no larger; else an ExperimentError that
    says what it is: missing, a link to nothing, a folder, a device or pipe, too large (its size)."""
    if path.is_symlink() and not path.exists():
        raise ExperimentError(f"{path}: a symbolic link to nothing (or to itself): give the {what} file itself")
    if not path.exists():
        raise ExperimentError(f"{path}: no such {what} file")
    if path.is_dir():
        raise ExperimentError(f"{path}: is a folder; give the {what} file itself")
    if not path.is_file():
        raise ExperimentError(f"{path}: not a regular file (a device or a pipe?): give the {what} file itself")
    limit = MAX_FILE_BYTES[what]
    try:
        size = path.stat().st_size
    except OSError as error:
        raise ExperimentError(f"{path}: cannot be read: {error.strerror}") from None
    if size > limit:
        raise ExperimentError(f"{path}: {_size(size)}, more than the {_size(limit)} a {what} file may be")
    return limit


def _size(count: int) -> str:
    return f"{count / (1 << 20):.1f} MiB" if count >= 1 << 20 else f"{count / 1024:.0f} KiB"


def _check_line_lengths(path: Path, raw: bytes) -> None:
    """Raises ExperimentError naming the first line longer than MAX_LINE_BYTES (line ends: LF,
    CR LF or a bare CR), scanning 16 MiB at a time so the scan's arrays stay small."""
    if len(raw) <= MAX_LINE_BYTES:
        return
    chunk = 16 << 20
    ends = [np.array([-1])]
    for start in range(0, len(raw), chunk):
        block = np.frombuffer(raw, dtype=np.uint8, count=min(chunk, len(raw) - start), offset=start)
        ends.append(np.flatnonzero((block == ord("\n")) | (block == ord("\r"))) + start)
    ends.append(np.array([len(raw)]))
    bounds = np.concatenate(ends)
    long_lines = np.flatnonzero(np.diff(bounds) - 1 > MAX_LINE_BYTES)
    if long_lines.size:
        first = int(long_lines[0])
        begins = int(bounds[first]) + 1
        length = int(bounds[first + 1]) - begins
        line = raw.count(b"\n", 0, begins) + 1
        raise ExperimentError(
            f"{path}:{line}: a line of {_size(length)}, more than the "
            f"{_size(MAX_LINE_BYTES)} a line may be (is this the right file?)"
        )


def _ends_unterminated(path: Path) -> bool:
    """Whether the file's last byte is not a line end."""
    with path.open("rb") as handle:
        handle.seek(0, 2)
        if handle.tell() == 0:
            return False
        handle.seek(-1, 2)
        return handle.read(1) not in (b"\n", b"\r")


def _parse_row(path: Path, line: int, header: list[str], row: list[str]) -> list[float]:
    if len(row) != len(header):
        raise ExperimentError(f"{path}:{line}: {len(row)} values, the header has {len(header)}")
    parsed = []
    for column, (name, cell) in enumerate(zip(header, row), start=1):
        try:
            value = float(cell)
        except ValueError:
            raise ExperimentError(
                f"{path}:{line}: column {column} ({name}) = {cell.strip()!r} is not a number"
            ) from None
        if not math.isfinite(value):
            raise ExperimentError(f"{path}:{line}: column {column} ({name}) = {cell.strip()!r} is not finite")
        parsed.append(value)
    return parsed


#: Rows formatted at a time by write_series.
WRITE_BLOCK_ROWS = 1 << 16


def write_series(path: str | Path, columns: dict[str, np.ndarray], digits: int = 10) -> None:
    """Writes columns of equal length to CSV with a header row, `digits` significant digits."""
    series = {name: np.asarray(column, dtype=float) for name, column in columns.items()}
    rows = len(next(iter(series.values()))) if series else 0
    with SeriesWriter(path, list(series), digits) as writer:
        # In blocks of rows, so that a long test's text never stands in memory whole.
        for start in range(0, rows, WRITE_BLOCK_ROWS):
            writer.write({name: column[start : start + WRITE_BLOCK_ROWS] for name, column in series.items()})


class SeriesWriter:
    """Writes a CSV block of rows by block, as they are computed, in write_series's format (the
    same bytes): a header row of `names`, then `digits` significant digits ("%g"), csv's line
    ends (CRLF). A context manager; a failure inside it removes the partial file, so that a
    simulation that stops half-way leaves no CSV to mistake for its result.

        with SeriesWriter("out.csv", ["time_s", "force_N"]) as writer:
            writer.write({"time_s": t, "force_N": f})  # as often as there are blocks
    """

    def __init__(self, path: str | Path, names: Sequence[str], digits: int = 10):
        self.path = Path(path)
        self.names = list(names)
        self.digits = digits
        self.rows = 0  # written so far
        self._handle = None

    def __enter__(self) -> SeriesWriter:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._handle = self.path.open("w", newline="")
        csv.writer(self._handle).writerow(self.names)
        return self

    def write(self, columns: Mapping[str, np.ndarray]) -> None:
        """Appends rows: `columns` holds each name's values for them, all of one length."""
        block = np.column_stack([np.asarray(columns[name], dtype=float) for name in self.names])
        np.savetxt(self._handle, block, fmt=f"%.{self.digits}g", delimiter=",", newline="\r\n")
        self.rows += block.shape[0]

    def __exit__(self, kind, error, trace) -> None:
        self._handle.close()
        if error is not None:
            self.path.unlink(missing_ok=True)


def write_experiment(
    path: str | Path,
    sections: Mapping[str, Mapping[str, object]],
    columns: Mapping[str, np.ndarray] | None = None,
    comments: Sequence[str] = (),
) -> Path:
    """Writes an experiment in DESIGN.md's format: the TOML at `path` and, given `columns`, its CSV
    beside it with the same stem (:func:`write_series`), which ``[test] data`` then names. The one
    writer of experiment files: ``pamkit align``, ``pamkit synth`` and the thesis's data use it.

    Args:
        sections: section name -> {key: value}, written in the order given; each section one of
            :data:`EXPERIMENT_SECTIONS`, and ``[test]``'s keys those :data:`TEST_KEYS` names.
            Values: bool, int, float (finite), str, or a list of those.
        columns: the measured series; without them ``[test] data`` must be given.
        comments: lines written as ``# ...`` at the top.

    Returns:
        The CSV's path (the one ``[test] data`` names).

    Raises:
        ValueError: naming the section and key of a value TOML cannot hold or the reader would refuse.
    """
    path = Path(path)
    sections = {name: dict(table) for name, table in sections.items()}
    for name in sections:
        if name not in EXPERIMENT_SECTIONS:
            known = ", ".join(EXPERIMENT_SECTIONS)
            raise ValueError(f"{path}: cannot write section [{name}] (an experiment has {known})")
    test = sections.setdefault("test", {})
    if columns is not None:
        data = path.with_suffix(".csv")
        test.pop("data", None)
        test["data"] = data.name  # last, as DESIGN.md shows it
    elif "data" in test:
        data = path.parent / test["data"]
    else:
        raise ValueError(f"{path}: an experiment names its data: give the columns or [test] data")
    for key in test:
        if key not in TEST_KEYS:
            raise ValueError(f"{path}: cannot write [test] {key} (known: {', '.join(TEST_KEYS)})")
    lines = [f"# {line}" if line else "#" for comment in comments for line in comment.split("\n")]
    for name, table in sections.items():
        lines += ["", f"[{name}]"] if lines else [f"[{name}]"]
        lines += [f"{_toml_key(key)} = {_toml_value(value, f'[{name}] {key}')}" for key, value in table.items()]
    if columns is not None:
        write_series(data, columns)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return data


_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")
# Integers beyond 2^53 are not all floats; written as floats they read back as they were.
_LARGEST_EXACT_INTEGER = 2**53


def _toml_key(key: str) -> str:
    return key if _BARE_KEY.fullmatch(key) else _toml_string(key)


def _toml_string(text: str) -> str:
    # JSON's escapes are TOML's (\", \\, \n, \uXXXX for the other controls) except that TOML
    # also forbids a raw DEL.
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


def _toml_value(value: object, where: str) -> str:
    """One value as TOML; a number whose value is whole is written as an integer (`216`, not
    `216.0`: the reader takes both as floats, and lab files write counts that way)."""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, numbers.Real):
        number = float(value)
        if not math.isfinite(number):
            raise ValueError(f"cannot write {where} = {value!r}: an experiment's numbers are finite")
        if number.is_integer() and abs(number) < _LARGEST_EXACT_INTEGER:
            return str(int(number))
        return repr(number)
    if isinstance(value, str):
        return _toml_string(value)
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml_value(item, where) for item in value) + "]"
    raise ValueError(f"cannot write {where} = {value!r} to TOML (a number, text, true/false or a list of them)")
