"""Measured (or planned) experiments: a TOML file describing the muscle and the test, naming a
CSV of what was measured (DESIGN.md, "A measured dataset").

Every problem is reported as an :class:`ExperimentError` (a ``ValueError``) that names the
file, and for CSV data the line and column.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

try:
    import tomllib
except ModuleNotFoundError:  # Python < 3.11
    import tomli as tomllib

from pamkit._core import FrictionParams, GasParams, GasProcess, MuscleBuild
from pamkit.units import KELVIN_AT_ZERO_CELSIUS

REQUIRED_COLUMNS = ("time_s", "elongation_m")
OPTIONAL_COLUMNS = ("force_N", "pressure_kPa", "temperature_C")
GAS_MODES = ("sealed", "supplied")

# [test] keys, their meaning, and whether they must be present.
TEST_KEYS = {
    "inflation_pressure_kPa": (True, "gauge pressure after inflation, before the first stretch [kPa]"),
    "ambient_temperature_C": (True, "ambient temperature, the gas's initial temperature [°C]"),
    "data": (True, "CSV file, relative to the TOML file"),
    "gas": (False, '"sealed" (default) or "supplied"'),
    "initial_length_m": (False, "muscle length at zero elongation [m]"),
    "description": (False, "free text: where the test comes from"),
}
# [gas] keys beyond GasParams' fields: the process by name.
GAS_PROCESS_KEY = "process"


class ExperimentError(ValueError):
    """An experiment file or its data cannot be used; the message says where."""


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
    columns: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def time_s(self) -> np.ndarray:
        return self.columns["time_s"]

    @property
    def elongation_m(self) -> np.ndarray:
        return self.columns["elongation_m"]

    def measured(self) -> list[str]:
        """The optional channels present in the data."""
        return [name for name in OPTIONAL_COLUMNS if name in self.columns]


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


def load_experiment(path: str | Path) -> Experiment:
    """Reads an experiment TOML and its CSV.

    Raises:
        ExperimentError: naming the file (and line and column for CSV data) of the first problem.
    """
    path = Path(path)
    try:
        with path.open("rb") as handle:
            document = tomllib.load(handle)
    except FileNotFoundError:
        raise ExperimentError(f"{path}: no such experiment file") from None
    except tomllib.TOMLDecodeError as error:
        raise _fail(path, f"not valid TOML: {error}") from None

    known_sections = {"muscle", "test", "friction", "gas"}
    for section in document:
        if section not in known_sections:
            raise _fail(path, f"unknown section [{section}] (known: {', '.join(sorted(known_sections))})")
    for section in ("muscle", "test"):
        if section not in document:
            raise _fail(path, f"missing section [{section}]")

    build = _fill_struct(path, "muscle", document["muscle"], MuscleBuild())
    friction = _fill_struct(path, "friction", document.get("friction", {}), FrictionParams())
    gas_table = document.get("gas", {})
    gas_params = GasParams()
    if GAS_PROCESS_KEY in gas_table:
        name = gas_table[GAS_PROCESS_KEY]
        if name not in GasProcess.__members__:
            raise _fail(path, f"[gas] process = {name!r} must be one of {', '.join(GasProcess.__members__)}")
        gas_params.process = GasProcess.__members__[name]
    _fill_struct(path, "gas", gas_table, gas_params, extra_keys=(GAS_PROCESS_KEY,))

    test = document["test"]
    for key in test:
        if key not in TEST_KEYS:
            raise _fail(path, f"unknown key [test] {key} (known: {', '.join(TEST_KEYS)})")
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
    if not isinstance(test["data"], str):
        raise _fail(path, f"[test] data = {test['data']!r} must be a file name")
    data_path = (path.parent / test["data"]).resolve()

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
    )
    experiment.columns = read_series(data_path)
    if gas == "supplied" and "pressure_kPa" not in experiment.columns:
        raise _fail(data_path, 'a "supplied" test drives the model with pressure_kPa: the column is missing')
    return experiment


def read_series(path: str | Path) -> dict[str, np.ndarray]:
    """Reads a measured-data CSV: a header row, then numbers. Requires time_s and elongation_m,
    accepts force_N, pressure_kPa, temperature_C; time must increase.

    Raises:
        ExperimentError: naming the file, line and column of the first bad value.
    """
    path = Path(path)
    try:
        handle = path.open(newline="")
    except FileNotFoundError:
        raise ExperimentError(f"{path}: no such data file") from None
    with handle:
        reader = csv.reader(handle)
        try:
            header = [name.strip() for name in next(reader)]
        except StopIteration:
            raise ExperimentError(f"{path}: empty file, expected a header row") from None
        known = REQUIRED_COLUMNS + OPTIONAL_COLUMNS
        for number, name in enumerate(header, start=1):
            if name not in known:
                raise ExperimentError(f"{path}:1: column {number} '{name}' is not a known channel ({', '.join(known)})")
            if header.count(name) > 1:
                raise ExperimentError(f"{path}:1: column '{name}' appears twice")
        for name in REQUIRED_COLUMNS:
            if name not in header:
                raise ExperimentError(f"{path}:1: required column '{name}' is missing")
        values: list[list[float]] = []
        for row in reader:
            line = reader.line_num
            if not row or all(not cell.strip() for cell in row):
                continue
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
            if values and parsed[header.index("time_s")] <= values[-1][header.index("time_s")]:
                raise ExperimentError(
                    f"{path}:{line}: column {header.index('time_s') + 1} (time_s) = {parsed[header.index('time_s')]} "
                    "does not increase"
                )
            values.append(parsed)
    if len(values) < 2:
        raise ExperimentError(f"{path}: needs at least 2 data rows, found {len(values)}")
    table = np.asarray(values)
    return {name: table[:, index].copy() for index, name in enumerate(header)}


def write_series(path: str | Path, columns: dict[str, np.ndarray], digits: int = 10) -> None:
    """Writes columns of equal length to CSV with a header row, `digits` significant digits."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    names = list(columns)
    table = np.column_stack([np.asarray(columns[name], dtype=float) for name in names])
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(names)
        writer.writerows([[f"{value:.{digits}g}" for value in row] for row in table])
