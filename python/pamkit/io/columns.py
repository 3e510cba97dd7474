"""The columns of a measured time series: their names inside pamkit, where every value is SI
(the model's channels, declared once in C++: effect.hpp's measured_channels), and their names in
a file, where a person reads them (gauge pressure in kPa, temperature in degC); and the one
conversion between the two, which the readers apply to what they read and the writers to what
they write. Nothing between a reader and a writer converts a unit."""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from pamkit._core import measured_channels
from pamkit.io.schema import TABLE_COLUMNS
from pamkit.units import (
    KELVIN_AT_ZERO_CELSIUS,
    KILOPASCAL_PER_BAR,
    KILOPASCAL_PER_PSI,
    MILLIMETRE_PER_METRE,
    PASCAL_PER_KILOPASCAL,
)

# The time base and the crosshead's motion are required; the channels the instruments read are
# optional. Every module that lists them imports them from here.
REQUIRED_COLUMNS = ("time_s", "elongation_m")
OPTIONAL_COLUMNS = tuple(measured_channels())
SERIES_COLUMNS = REQUIRED_COLUMNS + OPTIONAL_COLUMNS
# The channels the Arduino logger records (the 61CP transducer on A0, the TMP36 on A1); the
# tensile machine records the others.
LOGGER_CHANNELS = ("gauge_pressure_Pa", "temperature_K")


@dataclass(frozen=True)
class FileUnit:
    """A column whose file unit is not SI: its name in a file, its name in SI, the file's unit
    as a person reads it, and the value in each unit of a value in the other."""

    file_name: str
    si_name: str
    unit: str
    to_si: Callable
    from_si: Callable


FILE_UNITS = (
    FileUnit(
        "pressure_kPa",
        "gauge_pressure_Pa",
        "kPa",
        lambda kilopascals: kilopascals * PASCAL_PER_KILOPASCAL,
        lambda pascals: pascals / PASCAL_PER_KILOPASCAL,
    ),
    FileUnit(
        "temperature_C",
        "temperature_K",
        "°C",
        lambda celsius: celsius + KELVIN_AT_ZERO_CELSIUS,
        lambda kelvin: kelvin - KELVIN_AT_ZERO_CELSIUS,
    ),
)
_BY_FILE_NAME = {unit.file_name: unit for unit in FILE_UNITS}
_BY_SI_NAME = {unit.si_name: unit for unit in FILE_UNITS}


def file_name(name: str) -> str:
    """A column's name in a file (pressure_kPa for gauge_pressure_Pa; time_s for time_s)."""
    return _BY_SI_NAME[name].file_name if name in _BY_SI_NAME else name


def file_unit(name: str) -> str | None:
    """The unit a file (and a figure) gives the SI column `name` in, where it is not SI ("kPa"
    for gauge_pressure_Pa); None for a column a file keeps in SI."""
    return _BY_SI_NAME[name].unit if name in _BY_SI_NAME else None


def si_name(name: str) -> str:
    """A file column's name inside pamkit (gauge_pressure_Pa for pressure_kPa)."""
    return _BY_FILE_NAME[name].si_name if name in _BY_FILE_NAME else name


def value_to_si(name: str, value):
    """A value (or array) of the file column `name` in SI."""
    return _BY_FILE_NAME[name].to_si(value) if name in _BY_FILE_NAME else value


def value_from_si(name: str, value):
    """A value (or array) of the SI column `name` in its file's unit."""
    return _BY_SI_NAME[name].from_si(value) if name in _BY_SI_NAME else value


def difference_from_si(name: str, value):
    """A difference (an error, a noise) of the SI column `name` in its file's unit: scaled, never
    offset (an RMSE of 0.2 K is 0.2 °C)."""
    return value_from_si(name, value) - value_from_si(name, 0.0)


def to_si(columns: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Columns as read from a file, renamed and converted to SI, in their order."""
    return {si_name(name): value_to_si(name, values) for name, values in columns.items()}


def to_file(columns: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
    """SI columns renamed and converted to their file units, in their order."""
    return {file_name(name): value_from_si(name, values) for name, values in columns.items()}


# The optional columns as a file names them.
FILE_OPTIONAL_COLUMNS = tuple(file_name(name) for name in OPTIONAL_COLUMNS)
LOGGER_FILE_COLUMNS = tuple(file_name(name) for name in LOGGER_CHANNELS)


# A transducer that reads absolute pressure (an MPX...AP on an Arduino): a file may say so by the
# column's name; it is read as the gauge pressure, less [gas] atmospheric_pressure_Pa (to_gauge).
ABSOLUTE_PRESSURE = "absolute_pressure_kPa"


@dataclass(frozen=True)
class OtherUnit:
    """A column a file may give in another unit than pamkit's file name says (a laser in
    millimetres, a regulator in bar): its name there, the column pamkit's files name it, and the
    factor that takes the one's values to the other's. The readers convert it on reading; the
    writers always write the column pamkit names."""

    file_name: str
    column: str
    factor: float


OTHER_UNITS = (
    OtherUnit("time_ms", "time_s", 1.0 / 1000.0),
    OtherUnit("elongation_mm", "elongation_m", 1.0 / MILLIMETRE_PER_METRE),
    OtherUnit("length_mm", "length_m", 1.0 / MILLIMETRE_PER_METRE),
    OtherUnit("contraction_mm", "contraction_m", 1.0 / MILLIMETRE_PER_METRE),
    OtherUnit("force_kN", "force_N", 1000.0),
    OtherUnit("pressure_bar", "pressure_kPa", KILOPASCAL_PER_BAR),
    OtherUnit("pressure_MPa", "pressure_kPa", 1000.0),
    OtherUnit("pressure_psi", "pressure_kPa", KILOPASCAL_PER_PSI),
    OtherUnit("absolute_pressure_bar", "absolute_pressure_kPa", KILOPASCAL_PER_BAR),
    OtherUnit("absolute_pressure_MPa", "absolute_pressure_kPa", 1000.0),
    OtherUnit("absolute_pressure_psi", "absolute_pressure_kPa", KILOPASCAL_PER_PSI),
)
_OTHER_BY_FILE_NAME = {unit.file_name: unit for unit in OTHER_UNITS}


def in_pamkit_units(name: str) -> tuple[str, float]:
    """The column a file's `name` is in pamkit's files, and the factor to its unit there
    (("length_m", 0.001) for length_mm; (name, 1.0) for a name pamkit's files use)."""
    unit = _OTHER_BY_FILE_NAME.get(name)
    return (unit.column, unit.factor) if unit else (name, 1.0)


# Every name a data file of pamkit's may give a column, by its lower case: a spelling that differs
# only in case ("Pressure_kPa", "LENGTH_MM") is that name.
_FILE_NAMES = {
    name.lower(): name
    for name in (
        *REQUIRED_COLUMNS,
        *FILE_OPTIONAL_COLUMNS,
        *(column for columns in TABLE_COLUMNS.values() for column in columns),
        *(unit.file_name for unit in OTHER_UNITS),
        "contraction_m",
        "contraction_percent",
        ABSOLUTE_PRESSURE,
    )
}
# A name with its unit in brackets, as spreadsheets and loggers head a column: "Pressure [kPa]",
# "Force (N)", "Temperature (°C)".
_BRACKETED = re.compile(r"^(?P<name>[A-Za-z][A-Za-z ]*?)\s*(?:\[(?P<a>[^\]]+)\]|\((?P<b>[^)]+)\))$")
_UNIT_SPELLINGS = {"sec": "s", "°c": "c", "degc": "c", "deg c": "c", "° c": "c", "%": "percent"}
_KNOWN = frozenset(_FILE_NAMES.values())


def pamkit_spelling(cell: str) -> str:
    """A header cell as pamkit's files spell it: "Pressure [kPa]", "Force (N)", "Temperature (°C)"
    and "LENGTH_MM" are pressure_kPa, force_N, temperature_C and length_mm (the name before the
    brackets, its spaces as underscores, the unit after it). A cell that spells no name pamkit
    reads comes back as it is, for the reader's error to quote."""
    stripped = cell.strip()
    match = _BRACKETED.match(stripped)
    if match:
        unit = (match["a"] or match["b"]).strip().lower()
        stripped = f"{match['name'].strip().replace(' ', '_')}_{_UNIT_SPELLINGS.get(unit, unit)}"
    return _FILE_NAMES.get(stripped.lower(), cell)


def with_units_row(names: list[str], units: list[str]) -> list[str] | None:
    """A header of names completed by the line of units under it, as a logger writes "Time, Force"
    over "s, N" (or "(s), (N)"): each name with its unit in brackets, for pamkit_spelling to read;
    a name pamkit already reads stays as it is where the unit under it is its own ("time_s" over
    "s"). None where `units` is no such line: it has another width, holds a number or nothing,
    gives a name pamkit reads another unit, or completes no name.
    """
    if len(units) != len(names) or not any(u.strip() for u in units) or any(_is_number(u) for u in units):
        return None
    out = []
    for name, cell in zip(names, units):
        unit = cell.strip().strip("()[]").strip()
        if not unit or not name.strip():
            out.append(name)
        elif pamkit_spelling(name) in _KNOWN:
            if not _is_its_unit(pamkit_spelling(name), unit):
                return None
            out.append(name)
        else:
            out.append(f"{name.strip()} [{unit}]")
    return out if any(pamkit_spelling(cell) in _KNOWN for cell in out) else None


def _is_its_unit(known_name: str, unit: str) -> bool:
    """Whether `unit` ("kPa", "°C") is the one a name of pamkit's files carries ("pressure_kPa")."""
    suffix = known_name.rsplit("_", 1)[-1].lower()
    return _UNIT_SPELLINGS.get(unit.lower(), unit.lower()) == suffix


def _is_number(cell: str) -> bool:
    try:
        float(cell.strip().replace(",", "."))
    except ValueError:
        return False
    return True


def to_gauge(columns: dict[str, np.ndarray], atmospheric_pressure_Pa: float) -> dict[str, np.ndarray]:
    """SI `columns` with an absolute pressure (ABSOLUTE_PRESSURE, still in kPa) turned into the
    gauge pressure pamkit works in, less the atmosphere's."""
    if ABSOLUTE_PRESSURE in columns:
        absolute = columns.pop(ABSOLUTE_PRESSURE)
        columns["gauge_pressure_Pa"] = absolute * PASCAL_PER_KILOPASCAL - atmospheric_pressure_Pa
    return columns


def other_units_of(columns) -> list[str]:
    """The other names a file may give `columns` (pamkit's file names) under, in OTHER_UNITS' order."""
    return [unit.file_name for unit in OTHER_UNITS if unit.column in columns]


# The unit of each column inside pamkit, SI, as its name's suffix says: a time series' and a
# static table's (length_m, diameter_m), as an Experiment holds them and pamkit.simulate returns them.
COLUMN_UNITS = {
    "time_s": "s",
    "elongation_m": "m",
    "length_m": "m",
    "diameter_m": "m",
    "force_N": "N",
    "gauge_pressure_Pa": "Pa",
    "temperature_K": "K",
}
