"""What each kind of test reads from its data file: a measured time series (pamkit's CSV, a
spreadsheet's with ";" and decimal commas, or a tensile machine's export), a static table of
settled rows, an isotonic test's rows; and the check that each value's size fits its unit. Each
returns its columns in SI (:func:`pamkit.io.columns.to_si`): a file's pressure_kPa is read as
gauge_pressure_Pa, its temperature_C as temperature_K. The CSV itself is read by csv_reader.py.
"""

from __future__ import annotations

import csv
import warnings
from pathlib import Path

import numpy as np

from pamkit._core import GasParams
from pamkit.io.columns import (
    ABSOLUTE_PRESSURE,
    FILE_OPTIONAL_COLUMNS,
    REQUIRED_COLUMNS,
    file_name,
    in_pamkit_units,
    other_units_of,
    to_gauge,
    to_si,
    value_from_si,
)
from pamkit.io.csv_reader import SNIFF_BYTES, delimiter_of, header_line, header_of, read_columns
from pamkit.io.guards import ExperimentError, ExperimentWarning
from pamkit.io.machine import looks_like_export, read_machine_export
from pamkit.io.schema import TABLE_COLUMNS, TEST_CONDITIONS

STANDARD_ATMOSPHERE_PA = GasParams().atmospheric_pressure_Pa  # where a file's [gas] says none

# Values whose size says a file's unit is wrong: (SI column, lowest, highest plausible value in
# the file's unit, what it looks like instead). No pneumatic muscle holds more than the highest
# inflation pressure a file may declare (20 bar; a Festo fluidic muscle runs to 6-8 bar).
PLAUSIBLE_VALUES = {
    "elongation_m": (-0.5, 0.5, "millimetres"),
    "force_N": (-1e4, 1e5, "the wrong unit"),
    "gauge_pressure_Pa": (-101.0, TEST_CONDITIONS["inflation_pressure_kPa"][1], "pascals or psi"),
    "temperature_K": (-50.0, 150.0, "kelvin"),
}


def check_units(data_path: Path, columns: dict[str, np.ndarray]) -> None:
    """Raises an ExperimentError naming the file, row and column of the first value of the SI
    `columns` whose size says its file's unit is wrong (an elongation in mm, a pressure in Pa, a
    temperature in K), as the file gives it, and the units a file may give that column in."""
    names = list(columns)
    for name, (low, high, looks_like) in PLAUSIBLE_VALUES.items():
        if name not in columns:
            continue
        values = value_from_si(name, columns[name])
        bad = np.flatnonzero((values < low) | (values > high))
        if bad.size:
            row = int(bad[0])
            others = other_units_of((file_name(name),))
            raise ExperimentError(
                f"{data_path}:{row + 2}: column {names.index(name) + 1} ({file_name(name)}) = {values[row]:g} is "
                f"outside [{low:g}, {high:g}]: is it in {looks_like}?"
                + (f" (a file may give {file_name(name)} as {', '.join(others)})" if others else "")
            )


# A muscle pulls: its force is tension, positive. A record that pushes this many times harder than
# it ever pulls, and by more than PUSH_NOTICED_N, reads tension as negative (a load cell mounted
# or set up the other way), or holds a braid that can push (a model's, not a real muscle's).
PUSH_OVER_PULL = 5.0
PUSH_NOTICED_N = 20.0


def check_force_sign(data_path: Path, columns: dict[str, np.ndarray]) -> None:
    """Warns (ExperimentWarning) where the force pushes far harder than it pulls (PUSH_OVER_PULL):
    pamkit's force is tension positive, and a load cell that reads it negative turns every
    prediction's sign."""
    if "force_N" not in columns or columns["force_N"].size == 0:
        return
    force = columns["force_N"]
    push, pull = -float(np.min(force)), float(np.max(force))
    if push > PUSH_NOTICED_N and push > PUSH_OVER_PULL * max(pull, 1.0):
        warnings.warn(
            f"{data_path}: force_N pushes down to {-push:.4g} N and pulls at most {pull:.4g} N: pamkit's force is "
            "tension positive (a muscle pulls). Does the load cell read tension as negative? Then give the force "
            "with its sign turned",
            ExperimentWarning,
            3,
        )


def read_series(
    path: str | Path,
    specimen: str | None = None,
    ignore: tuple[str, ...] = (),
    atmospheric_pressure_Pa: float = STANDARD_ATMOSPHERE_PA,
) -> dict[str, np.ndarray]:
    """Reads a measured-data CSV: a header row, then numbers. Requires time_s and elongation_m,
    accepts force_N, pressure_kPa, temperature_C; time must increase. Returns the columns in SI
    (time_s, elongation_m, and as present force_N, gauge_pressure_Pa, temperature_K). Columns
    named in `ignore` (as the file names them: [test] ignore_columns) are not read; an absolute
    pressure (absolute_pressure_kPa) is read as the gauge one above `atmospheric_pressure_Pa`.

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
        columns = read_machine_export(path, specimen).columns
        return {"time_s": columns["time_s"], "elongation_m": columns["extension_m"], "force_N": columns["force_N"]}
    if specimen is not None:
        raise ExperimentError(
            f"{path}: [test] specimen = {specimen!r} chooses among a tensile machine's specimens; this is pamkit's CSV "
            "of one test: leave it out"
        )
    line, header = header_of(path, ignore)
    optional = tuple(_pressure_measure(path, line, header) if c == "pressure_kPa" else c for c in FILE_OPTIONAL_COLUMNS)
    columns = read_columns(path, REQUIRED_COLUMNS, optional, increasing="time_s", ignore=ignore)
    return to_gauge(to_si(columns), atmospheric_pressure_Pa)


def _pressure_measure(path: Path, line: int, header: list[str]) -> str:
    """pressure_kPa (gauge) or ABSOLUTE_PRESSURE, whichever the header gives; both is an error."""
    if "pressure_kPa" in header and ABSOLUTE_PRESSURE in header:
        raise ExperimentError(
            f"{path}:{line}: the pressure is given twice, as pressure_kPa (gauge) and {ABSOLUTE_PRESSURE}: give one"
        )
    return ABSOLUTE_PRESSURE if ABSOLUTE_PRESSURE in header else "pressure_kPa"


def _is_machine_export(path: Path) -> bool:
    """Whether a data file is a tensile machine's export rather than pamkit's CSV: its header line
    names none of pamkit's channels (in its units or another of OTHER_UNITS), and a machine's names
    row follows. ("time_s,elongation_m,force_lbf" is pamkit's CSV with a wrong name, not an export
    with units in its names.) A file that cannot be opened is left to read_columns, which says why."""
    try:
        if not path.is_file():
            return False
        with path.open("rb") as handle:
            _, header = header_line(handle.read(SNIFF_BYTES).decode("utf-8-sig", errors="replace"))
        cells = next(csv.reader([header], delimiter=delimiter_of(header)), [])
        names = [in_pamkit_units(name.strip())[0] for name in cells]
        if any(name in REQUIRED_COLUMNS + FILE_OPTIONAL_COLUMNS for name in names):
            return False  # pamkit's CSV, right or wrong: its errors name what to fix, no column is dropped
        _, spelled = header_of(path)  # a line of units under the names completes them
        if all(name in (*REQUIRED_COLUMNS, *FILE_OPTIONAL_COLUMNS, ABSOLUTE_PRESSURE) for name in spelled):
            return False  # pamkit's channels, spelled otherwise ("Pressure [kPa]"; "Pressure" over "bar"): all read
        return looks_like_export(path)
    except OSError:
        return False


def read_isotonic(
    path: str | Path,
    deflated_length_m: float,
    dynamic: bool = False,
    ignore: tuple[str, ...] = (),
    atmospheric_pressure_Pa: float = STANDARD_ATMOSPHERE_PA,
) -> dict[str, np.ndarray]:
    """An isotonic test's rows, in SI: the file's pressure_kPa (as gauge_pressure_Pa) and the
    muscle's length (LENGTH_MEASURES: its length_m, or its contraction from the deflated length);
    time_s when there is one (always, for a `dynamic` test: a load whose motion is integrated in
    time), not decreasing. Other channels of pamkit's are dropped with a warning (read_table)."""
    path = Path(path)
    line, header = header_of(path, ignore)
    if dynamic and "time_s" not in header:
        raise ExperimentError(
            f"{path}:{line}: [test] load_mass_kg integrates the load's motion in time: time_s is missing"
        )
    return read_table(
        path, ("pressure_kPa", "length_m"), "isotonic", True, ignore, deflated_length_m, atmospheric_pressure_Pa
    )


#: How a table may give the muscle's length: the length itself, or its contraction from the
#: deflated length, in metres or in per cent of that length (as a datasheet plots force against
#: contraction). Each in another unit too (length_mm, contraction_mm).
LENGTH_MEASURES = ("length_m", "contraction_m", "contraction_percent")


def _length_measure(path: Path, line: int, header: list[str], kind: str) -> str:
    """The one of LENGTH_MEASURES a table's header gives."""
    measures = [name for name in LENGTH_MEASURES if name in header]
    if len(measures) != 1:
        others = ", ".join(other_units_of(LENGTH_MEASURES))
        raise ExperimentError(
            f"{path}:{line}: this {kind} test gives the muscle's length as one of {', '.join(LENGTH_MEASURES)} (or "
            f"{others}); found {', '.join(measures) or 'none'}"
        )
    return measures[0]


def _as_length(path: Path, columns: dict[str, np.ndarray], deflated_length_m: float) -> dict[str, np.ndarray]:
    """`columns` with a contraction turned into the muscle's length_m."""
    if "contraction_m" in columns:
        columns["length_m"] = deflated_length_m - columns.pop("contraction_m")
    if "contraction_percent" in columns:
        percent = columns.pop("contraction_percent")
        if np.ptp(percent) > 0 and np.max(np.abs(percent)) <= 1.0:
            warnings.warn(
                f"{path}: contraction_percent stays within 1 % (at most {np.max(np.abs(percent)):.3g}): if these are "
                "fractions of the length (0.25 for 25 %), give them in per cent",
                ExperimentWarning,
                3,
            )
        columns["length_m"] = deflated_length_m * (1.0 - percent / 100.0)
    return columns


#: The channels a data file of pamkit's may name: a time series' and the tables'. A table reads
#: those its kind uses; the others are dropped with a warning (a logger's temperature beside an
#: isometric map), all but time_s, which orders its rows.
KNOWN_CHANNELS = tuple(
    dict.fromkeys(REQUIRED_COLUMNS + FILE_OPTIONAL_COLUMNS + tuple(c for cs in TABLE_COLUMNS.values() for c in cs))
)


def read_table(
    path: str | Path,
    columns: tuple[str, ...],
    kind: str = "table",
    keep_time: bool = False,
    ignore: tuple[str, ...] = (),
    deflated_length_m: float | None = None,
    atmospheric_pressure_Pa: float = STANDARD_ATMOSPHERE_PA,
) -> dict[str, np.ndarray]:
    """Reads a static table (one settled row per line) of a test of `kind`: `columns` (as the
    file names them), in any order; returns them in SI. A table's rows are in the order they were
    measured (the pressurise/vent branches follow it): a time_s column, if there is one, must not
    decrease, and is returned with `keep_time`. Any other of pamkit's channels (KNOWN_CHANNELS) is
    dropped with an ExperimentWarning naming it; columns named in `ignore` are not read. Given the
    `deflated_length_m`, the muscle's length_m may come as any of LENGTH_MEASURES; pressure_kPa may
    come as an absolute pressure, read as the gauge one above `atmospheric_pressure_Pa`.

    Raises:
        ExperimentError: naming the file, line and column of the first bad value.
    """
    path = Path(path)
    line, header = header_of(path, ignore)
    if deflated_length_m is not None and "length_m" in columns:
        measure = _length_measure(path, line, header, kind)
        columns = tuple(measure if name == "length_m" else name for name in columns)
    if "pressure_kPa" in columns:
        pressure = _pressure_measure(path, line, header)
        columns = tuple(pressure if name == "pressure_kPa" else name for name in columns)
    extra = tuple(name for name in KNOWN_CHANNELS if name in header and name not in columns)
    read = read_columns(path, columns, extra, increasing="time_s" if "time_s" in extra else None, ignore=ignore)
    unused = [name for name in extra if name != "time_s"]
    if unused:
        warnings.warn(
            f"{path}:{line}: {', '.join(unused)} {'is' if len(unused) == 1 else 'are'} not used by this {kind} test "
            f"(it reads {', '.join(columns)}); ignored",
            ExperimentWarning,
            2,
        )
    dropped = set(unused) | (set() if keep_time else {"time_s"})
    read = to_gauge(
        to_si({name: values for name, values in read.items() if name not in dropped}), atmospheric_pressure_Pa
    )
    return _as_length(path, read, deflated_length_m) if deflated_length_m is not None else read
