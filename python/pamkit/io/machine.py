"""Tensile machines' CSV exports: time, crosshead extension and load, in the machine's units.

Instron Bluehill ("Export raw data", CSV) and ZwickRoell testXpert II/III (ASCII export) write
the same layout: a block of metadata lines, a row of column names, a row of units, then one
row per sample. Bluehill quotes every cell and puts the units in parentheses; testXpert on a
German Windows separates with ";" (or tabs) and writes decimal commas; either may use the
other's habits depending on the export settings:

    "Sample I.D.","PAM2-03"                  Prüfer;Meier
    "Specimen Number","1"                    Prüfdatum;12.03.2024
                                             Prüfzeit;Standardweg;Standardkraft
    "Time","Extension","Load"                s;mm;N
    "(s)","(mm)","(N)"                       0,00;0,000;0,52
    "0.000","0.00000","0.51234"              0,10;0,250;1,87

Bluehill exports every specimen of a test into one file when asked to: each specimen's block
(its metadata, "Specimen Number" among it, then names, units and rows) follows the one before
after a blank line. :func:`read_machine_export` reads the specimen asked for, and refuses to
guess when there are several, naming them.

A plain CSV whose column names carry their units ("Time (s)", "Extension [mm]", "load_kN") is
read the same way, with no units row. The header row is found by its names (English or
German, :data:`ALIASES`), so neither format has to be declared.

Every problem is an :class:`~pamkit.io.guards.ExperimentError` (a ``ValueError``) naming the
file, and the line and column.
"""

from __future__ import annotations

import csv
import math
import re
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from pamkit.io.columns import ABSOLUTE_PRESSURE, LOGGER_FILE_COLUMNS, in_pamkit_units, pamkit_spelling
from pamkit.io.guards import ExperimentError, ExperimentWarning, read_text
from pamkit.units import NEWTON_PER_KILOGRAM_FORCE

# Column names, lowercased, units removed. testXpert's "Standardweg" / "Standard travel" is the
# crosshead travel since the test started; its absolute position ("Traversenweg absolut") is
# not an elongation and is left out on purpose.
ALIASES = {
    "time": ("time", "test time", "total time", "prüfzeit", "testzeit", "zeit"),
    "extension": (
        "extension",
        "displacement",
        "position",
        "elongation",
        "standard travel",
        "crosshead travel",
        "standardweg",
        "traversenweg",
    ),
    "load": ("load", "force", "standard force", "test force", "standardkraft", "prüfkraft", "kraft"),
}
# testXpert's own column names: a header using them is a testXpert export.
TESTXPERT_NAMES = {"prüfzeit", "test time", "standardweg", "standard travel", "standardkraft", "standard force"}
# Each unit's factor to SI, by quantity (lowercase; "µm" and "um" both for micrometres).
UNITS = {
    "time": {"s": 1.0, "sec": 1.0, "ms": 1e-3, "min": 60.0, "h": 3600.0},
    "extension": {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "µm": 1e-6, "um": 1e-6, "in": 0.0254},
    "load": {"n": 1.0, "kn": 1e3, "mn": 1e-3, "dan": 10.0, "lbf": 4.4482216152605, "kgf": NEWTON_PER_KILOGRAM_FORCE},
}
# The columns returned, by quantity.
OUTPUT_NAMES = {"time": "time_s", "extension": "extension_m", "load": "force_N"}
DELIMITERS = (";", "\t", ",")
# The metadata block above the names row: Bluehill's is some 30 lines, testXpert's fewer.
MAX_HEADER_LINES = 200

# "Time (s)", "Extension [mm]", "load_kN", or a bare name.
_NAME_AND_UNIT = re.compile(r"^\s*([^\W\d_][^()\[\]_]*?)\s*(?:[(\[]\s*([^()\[\]\s]+)\s*[)\]]|_([A-Za-zµ]+))?\s*$")
# A units-row cell: a unit, maybe in brackets, no digits ("(mm)", "[N]", "s", "%", "N/mm²", "").
_UNIT_CELL = re.compile(r"^\s*[(\[]?\s*[^\d()\[\]]*?\s*[)\]]?\s*$")


# The metadata line that names a block's specimen: "Specimen Number","2" (Bluehill), Probe;2 (testXpert).
SPECIMEN_NAMES = ("specimen number", "specimen", "specimen #", "probennummer", "probe", "probe nr.", "probennr.")


@dataclass
class MachineExport:
    """A tensile machine's export: its format and one specimen's columns in SI units (time_s
    [s], extension_m [m], force_N [N], one entry per sample, time increasing); `specimens` are
    the labels of every specimen the file holds (its "Specimen Number", else 1, 2, ... in
    order), `specimen` the one read."""

    format: str  # "instron_bluehill", "zwick_testxpert" or "units_in_names"
    columns: dict[str, np.ndarray]
    specimens: list[str] = field(default_factory=lambda: ["1"])
    specimen: str = "1"


def split_name(cell: str) -> tuple[str, str | None]:
    """A column name, lowercased, and the unit it carries ("Time (s)" -> ("time", "s"))."""
    match = _NAME_AND_UNIT.match(cell)
    if not match:
        return cell.strip().lower(), None
    return match.group(1).strip().lower(), (match.group(2) or match.group(3))


def _cells(line: str, delimiter: str) -> list[str]:
    return next(csv.reader([line], delimiter=delimiter), [])


def _find_columns(cells: list[str]) -> dict[str, int] | None:
    """The column of each quantity (the first whose name is one of its aliases), or None."""
    names = [split_name(cell)[0] for cell in cells]
    found = {}
    for quantity, aliases in ALIASES.items():
        at = next((number for number, name in enumerate(names) if name in aliases), None)
        if at is None:
            return None
        found[quantity] = at
    return found


def find_header(lines: list[str]) -> tuple[int, str, dict[str, int]] | None:
    """The names row of an export: (its index in `lines`, the delimiter, each quantity's
    column), or None when no line among the first MAX_HEADER_LINES names time, extension and
    load."""
    for index, line in enumerate(lines[:MAX_HEADER_LINES]):
        for delimiter in DELIMITERS:
            if delimiter not in line:
                continue
            columns = _find_columns(_cells(line, delimiter))
            if columns is not None:
                return index, delimiter, columns
    return None


def _lines(text: str) -> list[str]:
    """Physical lines, as an editor numbers them (LF, CR LF or a bare CR end a line)."""
    return text.replace("\r\n", "\n").replace("\r", "\n").split("\n")


def looks_like_export(path: Path) -> bool:
    """Whether the file has a machine export's names row (it is read only up to that row's
    neighbourhood: the first 64 KiB)."""
    with path.open("rb") as handle:
        head = handle.read(64 << 10)
    return find_header(_lines(_decode(head, path, strict=False))) is not None


def _decode(raw: bytes, path: Path, strict: bool = True) -> str:
    """UTF-8 (a byte-order mark dropped), else Windows-1252: both machines run on Windows and
    write the Western-European code page unless told otherwise ("Prüfzeit" is 0xFC there)."""
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        pass
    try:
        return raw.decode("cp1252")
    except UnicodeDecodeError as error:
        if not strict:
            return raw.decode("cp1252", errors="replace")
        line = raw[: error.start].count(b"\n") + 1
        raise ExperimentError(
            f"{path}:{line}: byte 0x{raw[error.start]:02x} is neither UTF-8 nor Windows-1252 text"
        ) from None


def _number(cell: str) -> float:
    """A cell's value; a decimal comma is read as a point ("0,25"); a cell with both a comma
    and a point (a thousands separator) is not a number."""
    cell = cell.strip()
    if "," in cell and "." not in cell:
        cell = cell.replace(",", ".")
    return float(cell)


def read_machine_export(path: str | Path, specimen: str | None = None) -> MachineExport:
    """Reads an Instron Bluehill or ZwickRoell testXpert CSV export (or a CSV whose column
    names carry their units): time, extension and load converted to s, m and N, of `specimen`
    (its label: the block's "Specimen Number", else its place, 1, 2, ...). A file of one
    specimen needs none; of several, one must be named.

    Raises:
        ExperimentError: naming the file, and the line and column, of the first problem: no
            names row, a missing or unknown unit, a cell that is not a number, time that does
            not increase, fewer than 2 samples; several specimens and none chosen, or one the
            file does not hold (naming those it holds).
    """
    path = Path(path)
    lines = _lines(read_text(path, "data", decode=lambda raw: _decode(raw, path)))
    found = find_header(lines)
    if found is None:
        raise ExperimentError(
            f"{path}: no row naming time, extension (or displacement, Standardweg) and load (or force, "
            f"Standardkraft) in its first {MAX_HEADER_LINES} lines: not a tensile machine's export"
        )
    blocks = _specimen_blocks(lines, *found)
    labels = [label for label, _, _ in blocks]
    if specimen is None and len(blocks) > 1:
        raise ExperimentError(
            f"{path}: holds {len(blocks)} specimens ({', '.join(labels)}): choose one "
            "(pamkit align --specimen LABEL; an experiment's [test] specimen = LABEL)"
        )
    if specimen is not None and str(specimen) not in labels:
        raise ExperimentError(f"{path}: no specimen {str(specimen)!r}; it holds {', '.join(labels)}")
    label, header_index, end = blocks[labels.index(str(specimen)) if specimen is not None else 0]
    export = _read_block(path, lines[:end], header_index, found[1], found[2])
    export.specimens, export.specimen = labels, label
    return export


def _specimen_blocks(
    lines: list[str], first_header: int, delimiter: str, columns: dict[str, int]
) -> list[tuple[str, int, int]]:
    """Each specimen's block: (its label, the index of its names row, the index after its last
    row). A block's rows end where the next specimen's metadata starts: the lines before its
    names row back to the last one whose time cell is a number."""
    time_words = ALIASES["time"]
    headers = [first_header] + [
        index
        for index in range(first_header + 1, len(lines))
        if delimiter in lines[index]
        and any(word in lines[index].lower() for word in time_words)  # cheap, before parsing the row
        and _find_columns(_cells(lines[index], delimiter)) == columns
    ]
    blocks = []
    for place, header in enumerate(headers):
        start = headers[place - 1] + 1 if place else 0
        metadata = header
        if place:
            while metadata > start and not _is_number_row(lines[metadata - 1], delimiter, columns["time"]):
                metadata -= 1
            blocks[-1] = (*blocks[-1][:2], metadata)
        label = _specimen_label(lines[metadata if place else 0 : header], delimiter) or str(place + 1)
        blocks.append((label, header, len(lines)))
    return blocks


def _is_number_row(line: str, delimiter: str, column: int) -> bool:
    cells = _cells(line, delimiter)
    try:
        _number(cells[column])
    except (IndexError, ValueError):
        return False
    return True


def _specimen_label(metadata: list[str], delimiter: str) -> str | None:
    """The specimen a block's metadata names ("Specimen Number","2"), or None."""
    for line in metadata:
        cells = [cell.strip() for cell in _cells(line, delimiter)]
        if len(cells) >= 2 and cells[0].lower().rstrip(":") in SPECIMEN_NAMES and cells[1]:
            return cells[1]
    return None


def _read_block(
    path: Path, lines: list[str], header_index: int, delimiter: str, columns: dict[str, int]
) -> MachineExport:
    """One specimen's block: the names row at `header_index` of `lines`, its units row, its rows
    to the end of `lines`."""
    header = _cells(lines[header_index], delimiter)
    units_row = None
    if header_index + 1 < len(lines):
        below = _cells(lines[header_index + 1], delimiter)
        if below and any(c.strip() for c in below) and all(_UNIT_CELL.match(c) for c in below):
            units_row = [c.strip().strip("()[]").strip() for c in below]

    # A channel of pamkit's beside the machine's (a logger's pressure merged in by hand) is not read
    # here: said, not dropped unseen, whether its name or its name with the unit under it spells it.
    # The machine's own others (strain, cycle) are its derivatives.
    def spells_a_channel(number: int, cell: str) -> bool:
        unit = units_row[number] if units_row is not None and number < len(units_row) else ""
        spellings = (cell, f"{cell.strip()} [{unit}]") if unit else (cell,)
        return any(
            in_pamkit_units(pamkit_spelling(c))[0] in (*LOGGER_FILE_COLUMNS, ABSOLUTE_PRESSURE) for c in spellings
        )

    unread = [
        cell.strip()
        for number, cell in enumerate(header)
        if number not in columns.values() and spells_a_channel(number, cell)
    ]
    if unread:
        warnings.warn(
            f"{path}:{header_index + 1}: read as a tensile machine's export, whose time, extension and load "
            f"pamkit reads; {', '.join(repr(cell) for cell in unread)} not read. Head every column as pamkit's "
            "CSV does (time_s, elongation_m, force_N, pressure_kPa, temperature_C, or 'Pressure [kPa]') and each "
            "is read",
            ExperimentWarning,
            3,
        )
    factors = {}
    for quantity, number in columns.items():
        unit = split_name(header[number])[1]
        line = header_index + 1
        if units_row is not None and number < len(units_row) and units_row[number]:
            unit, line = units_row[number], header_index + 2
        if unit is None:
            raise ExperimentError(
                f"{path}:{line}: column {number + 1} '{header[number].strip()}' has no unit "
                "(write it as 'Name (unit)' or in a units row below the names)"
            )
        factor = UNITS[quantity].get(unit.lower())
        if factor is None:
            raise ExperimentError(
                f"{path}:{line}: column {number + 1} '{header[number].strip()}': unknown unit '{unit}' "
                f"for {quantity} (known: {', '.join(UNITS[quantity])})"
            )
        factors[quantity] = factor
    first = header_index + (2 if units_row is not None else 1)
    values = {quantity: [] for quantity in columns}
    for line, text in enumerate(lines[first:], start=first + 1):
        row = _cells(text, delimiter)
        if not any(cell.strip() for cell in row):
            continue
        for quantity, number in columns.items():
            cell = row[number] if number < len(row) else ""
            try:
                value = _number(cell) * factors[quantity]
            except ValueError:
                raise ExperimentError(
                    f"{path}:{line}: column {number + 1} ({quantity}) = {cell.strip()!r} is not a number"
                ) from None
            if not math.isfinite(value):
                raise ExperimentError(
                    f"{path}:{line}: column {number + 1} ({quantity}) = {cell.strip()!r} is not finite"
                )
            if quantity == "time" and values["time"] and value <= values["time"][-1]:
                raise ExperimentError(f"{path}:{line}: column {number + 1} (time) = {cell.strip()!r} does not increase")
            values[quantity].append(value)
    if len(values["time"]) < 2:
        raise ExperimentError(f"{path}: needs at least 2 samples below the names row, found {len(values['time'])}")
    names = {split_name(header[number])[0] for number in columns.values()}
    if names & TESTXPERT_NAMES:
        source = "zwick_testxpert"
    elif units_row is not None:
        source = "instron_bluehill"
    else:
        source = "units_in_names"
    return MachineExport(source, {OUTPUT_NAMES[q]: np.asarray(v) for q, v in values.items()})
