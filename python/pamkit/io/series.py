"""The CSV readers: a measured time series (pamkit's CSV, a spreadsheet's with ";" and decimal
commas, or a tensile machine's export), a static table of settled rows, an isotonic test's rows.
Each returns its columns in SI (:func:`pamkit.io.columns.to_si`): a file's pressure_kPa is read
as gauge_pressure_Pa, its temperature_C as temperature_K.

A plain file is read in blocks by numpy; anything else, or a file with an error to name, row by
row with the csv module. Every problem is an :class:`~pamkit.io.guards.ExperimentError` naming
the file, line and column; a repair (a cut last line, repeated time stamps) is an
:class:`~pamkit.io.guards.ExperimentWarning` saying what was done.
"""

from __future__ import annotations

import csv
import io
import math
import re
import warnings
from pathlib import Path

import numpy as np

from pamkit.io.columns import (
    FILE_OPTIONAL_COLUMNS,
    REQUIRED_COLUMNS,
    file_name,
    in_pamkit_units,
    other_units_of,
    pamkit_spelling,
    to_si,
    value_from_si,
)
from pamkit.io.guards import (
    MAX_LINE_BYTES,
    ExperimentError,
    ExperimentWarning,
    checked_size,
    ends_unterminated,
    has_long_line,
    read_text,
)
from pamkit.io.machine import looks_like_export, read_machine_export
from pamkit.io.schema import TABLE_COLUMNS, TEST_CONDITIONS

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


def read_series(path: str | Path, specimen: str | None = None) -> dict[str, np.ndarray]:
    """Reads a measured-data CSV: a header row, then numbers. Requires time_s and elongation_m,
    accepts force_N, pressure_kPa, temperature_C; time must increase. Returns the columns in SI
    (time_s, elongation_m, and as present force_N, gauge_pressure_Pa, temperature_K).

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
    return to_si(_read_csv(path, REQUIRED_COLUMNS, FILE_OPTIONAL_COLUMNS, increasing="time_s"))


def _is_machine_export(path: Path) -> bool:
    """Whether a data file is a tensile machine's export rather than pamkit's CSV: its header line
    names none of pamkit's channels (in its units or another of OTHER_UNITS), and a machine's names
    row follows. ("time_s,elongation_m,force_lbf" is pamkit's CSV with a wrong name, not an export
    with units in its names.) A file that cannot be opened is left to _read_csv, which says why."""
    try:
        if not path.is_file():
            return False
        with path.open("rb") as handle:
            _, header_line = _header_line(handle.read(SNIFF_BYTES).decode("utf-8-sig", errors="replace"))
        cells = next(csv.reader([header_line], delimiter=_delimiter(header_line)), [])
        names = [in_pamkit_units(name.strip())[0] for name in cells]
        if any(name in REQUIRED_COLUMNS + FILE_OPTIONAL_COLUMNS for name in names):
            return False  # pamkit's CSV, right or wrong: its errors name what to fix, no column is dropped
        if all(pamkit_spelling(cell) != cell for cell in cells):
            return False  # pamkit's channels, spelled otherwise ("Pressure [kPa]"): every one is read
        return looks_like_export(path)
    except OSError:
        return False


def read_isotonic(path: str | Path, deflated_length_m: float, dynamic: bool = False) -> dict[str, np.ndarray]:
    """An isotonic test's rows, in SI: the file's pressure_kPa (as gauge_pressure_Pa) and the
    muscle's length_m, or its contraction_m from the deflated length (converted to length_m);
    time_s when there is one (always, for a `dynamic` test: a load whose motion is integrated in
    time), not decreasing. Other channels of pamkit's are dropped with a warning (read_table)."""
    path = Path(path)
    line, header = _header(path)
    measures = [name for name in ("length_m", "contraction_m") if name in header]
    if len(measures) != 1:
        raise ExperimentError(
            f"{path}:{line}: an isotonic test gives its length as one of length_m or contraction_m (or "
            f"{', '.join(other_units_of(('length_m', 'contraction_m')))}); found {', '.join(measures) or 'neither'}"
        )
    if dynamic and "time_s" not in header:
        raise ExperimentError(
            f"{path}:{line}: [test] load_mass_kg integrates the load's motion in time: time_s is missing"
        )
    columns = read_table(path, ("pressure_kPa", measures[0]), "isotonic", keep_time=True)
    if "contraction_m" in columns:
        columns["length_m"] = deflated_length_m - columns.pop("contraction_m")
    return columns


#: The channels a data file of pamkit's may name: a time series' and the tables'. A table reads
#: those its kind uses; the others are dropped with a warning (a logger's temperature beside an
#: isometric map), all but time_s, which orders its rows.
KNOWN_CHANNELS = tuple(
    dict.fromkeys(REQUIRED_COLUMNS + FILE_OPTIONAL_COLUMNS + tuple(c for cs in TABLE_COLUMNS.values() for c in cs))
)


def read_table(
    path: str | Path, columns: tuple[str, ...], kind: str = "table", keep_time: bool = False
) -> dict[str, np.ndarray]:
    """Reads a static table (one settled row per line) of a test of `kind`: `columns` (as the
    file names them), in any order; returns them in SI. A table's rows are in the order they were
    measured (the pressurise/vent branches follow it): a time_s column, if there is one, must not
    decrease, and is returned with `keep_time`. Any other of pamkit's channels (KNOWN_CHANNELS) is
    dropped with an ExperimentWarning naming it.

    Raises:
        ExperimentError: naming the file, line and column of the first bad value.
    """
    path = Path(path)
    line, header = _header(path)
    extra = tuple(name for name in KNOWN_CHANNELS if name in header and name not in columns)
    read = _read_csv(path, columns, extra, increasing="time_s" if "time_s" in extra else None)
    unused = [name for name in extra if name != "time_s"]
    if unused:
        warnings.warn(
            f"{path}:{line}: {', '.join(unused)} {'is' if len(unused) == 1 else 'are'} not used by this {kind} test "
            f"(it reads {', '.join(columns)}); ignored",
            ExperimentWarning,
            2,
        )
    dropped = set(unused) | (set() if keep_time else {"time_s"})
    return to_si({name: values for name, values in read.items() if name not in dropped})


def _header(path: Path) -> tuple[int, list[str]]:
    """The header's line number and names as pamkit's files name them (length_m for a file's
    length_mm)."""
    line, header_line = _header_line(read_text(path, "data"))
    cells = next(csv.reader([header_line], delimiter=_delimiter(header_line)), [])
    return line, [in_pamkit_units(pamkit_spelling(name))[0] for name in cells]


#: Bytes read to find a file's header line past its comment lines.
SNIFF_BYTES = 64 << 10

# A comment line: "#" first (after spaces or a byte-order mark), as a logger or a rig's software
# notes the date, the operator or a valve's switching. Its line end stays: lines keep their numbers.
_COMMENT_LINE = re.compile(r"(?:^|(?<=[\r\n]))[ \t\ufeff]*#[^\r\n]*")


def _is_skipped(line: str) -> bool:
    """Whether a line before the header is skipped: blank, or a comment."""
    stripped = line.strip(" \t\ufeff\r\n")
    return not stripped or stripped.startswith("#")


def _header_line(text: str) -> tuple[int, str]:
    """The header's line number (from 1) and text: the first line neither blank nor a comment.
    Lines end at LF, CR LF or a bare CR (an old Mac's or a logger's line end, which the csv module
    refuses inside a line)."""
    lines = re.split(r"\r\n|[\r\n]", text)
    for number, line in enumerate(lines, start=1):
        if not _is_skipped(line):
            return number, line
    return 1, lines[0]


def _delimiter(first_line: str) -> str:
    """The CSV's delimiter, from its header: European spreadsheets write "time_s;force_N" (and
    decimal commas), some machines tabs."""
    if ";" in first_line and "," not in first_line:
        return ";"
    return "\t" if "\t" in first_line else ","


def _read_csv(
    path: Path, required: tuple[str, ...], optional: tuple[str, ...], increasing: str | None
) -> dict[str, np.ndarray]:
    """The columns of a CSV: `required` ones and any of `optional`, `increasing` (if given) not
    decreasing, rows repeating it merged. A plain file is read in blocks by numpy; any other, or
    one with an error to name, row by row with the csv module."""
    columns = _read_plain_csv(path, required, optional, increasing)
    if columns is not None:
        return columns
    text = read_text(path, "data")
    delimiter = _delimiter(_header_line(text)[1])
    decimal_comma = delimiter != ","
    # Something numpy cannot read as it stands: row by row, to name the line and column.
    with io.StringIO(_COMMENT_LINE.sub("", text), newline="") as handle:
        reader = csv.reader(handle, delimiter=delimiter)
        cells: list[str] = []
        while not any(cell.strip() for cell in cells):
            try:
                cells = next(reader)
            except StopIteration:
                raise ExperimentError(f"{path}: empty file, expected a header row") from None
        header, factors = _checked_header(path, reader.line_num, cells, required, optional)
        named = [cell.strip() for cell in cells]  # as the file names them, for its errors
        order = header.index(increasing) if increasing else None
        rows = [(reader.line_num, row) for row in reader]
    cut_last_line = ends_unterminated(path)
    values: list[list[float]] = []
    merged: list[int] = []  # lines whose time stamp repeated the one before
    weight: list[int] = []  # rows averaged into each value row
    for position, (line, row) in enumerate(rows):
        if not row or all(not cell.strip() for cell in row):
            continue
        try:
            parsed = _parse_row(path, line, named, [c.replace(",", ".") for c in row] if decimal_comma else row)
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
                f"{path}:{line}: column {order + 1} ({named[order]}) = {parsed[order]} does not increase"
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
    return _in_pamkit_units({name: table[:, index].copy() for index, name in enumerate(header)}, factors)


def _shown(cell: str, limit: int = 40) -> str:
    """A cell as a message quotes it: on one line (a quoted cell may hold line ends), escaped
    where not printable (a stray byte-order mark), shortened past `limit` characters."""
    return repr(cell if len(cell) <= limit else cell[:limit] + "...")


def _checked_header(
    path: Path, line: int, cells: list[str], required: tuple[str, ...], optional: tuple[str, ...]
) -> tuple[list[str], list[float]]:
    """The header's channel names (on line `line`) as pamkit's files name them, each known and
    given once, the required ones all there; and the factor that takes each column to that name's
    unit (a column in another unit, OTHER_UNITS: length_mm is length_m, 0.001)."""
    known = required + optional
    header, factors = [], []
    for number, cell in enumerate(cells, start=1):
        name, factor = in_pamkit_units(pamkit_spelling(cell))
        if name not in known:
            others = other_units_of(known)
            raise ExperimentError(
                f"{path}:{line}: column {number} {_shown(cell.strip())} is not a known channel ({', '.join(known)}"
                + (f"; or in other units: {', '.join(others)})" if others else ")")
            )
        if name in header:
            first = cells[header.index(name)].strip()
            again = (
                f"column {_shown(first)} appears twice"
                if first == cell.strip()
                else f"columns {_shown(first)} and {_shown(cell.strip())} both give {name}"
            )
            raise ExperimentError(f"{path}:{line}: {again}")
        header.append(name)
        factors.append(factor)
    for name in required:
        if name not in header:
            raise ExperimentError(f"{path}:{line}: required column '{name}' is missing")
    return header, factors


def _in_pamkit_units(columns: dict[str, np.ndarray], factors: list[float]) -> dict[str, np.ndarray]:
    """Each column times its factor from _checked_header, where it is not 1."""
    return {name: values * f if f != 1.0 else values for (name, values), f in zip(columns.items(), factors)}


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
    limit = checked_size(path, "data")
    try:
        with path.open("rb") as handle:
            before = header_number = 0  # bytes and lines up to the header's end
            header_line = ""
            while _is_skipped(header_line):
                first = handle.readline(MAX_LINE_BYTES + 1)
                try:
                    header_line = first.decode("utf-8-sig" if not before else "utf-8")
                except UnicodeDecodeError:
                    return None
                if not header_line.endswith("\n") or not _is_plain(header_line):
                    return None
                before += len(first)
                header_number += 1
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
            handle.seek(before)
            columns = [np.empty(lines + 1) for _ in cells]  # and a last line without a line end
            size, rows_read, last = before, 0, ""
            while block := handle.read(READ_BLOCK_BYTES):
                if not block.endswith(b"\n"):
                    block += handle.readline(MAX_LINE_BYTES + 1)
                size += len(block)
                if size > limit or has_long_line(block):
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
    header, factors = _checked_header(path, header_number, cells, required, optional)
    named = [cell.strip() for cell in cells]
    if last.strip(delimiter + " \t"):
        line = header_number + rows_read + 1
        row = next(csv.reader([last], delimiter=delimiter))
        try:
            values = _parse_row(path, line, named, [c.replace(",", ".") for c in row] if delimiter != "," else row)
        except ExperimentError as error:
            warnings.warn(f"{path}:{line}: the last line is cut off ({error}); dropped", ExperimentWarning, 3)
        else:
            for column, value in zip(columns, values):
                column[rows_read] = value
            rows_read += 1
    for column in columns:
        column.resize(rows_read, refcheck=False)  # in place: nothing else refers to it
    checked = _checked_columns(path, dict(zip(header, columns)), header_number + 1, increasing, named)
    return _in_pamkit_units(checked, factors)


def _is_plain(text: str) -> bool:
    """No quoted cell (numpy's reader does not unquote), no carriage return but before a line feed."""
    return '"' not in text and text.count("\r") == text.count("\r\n")


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
    path: Path, columns: dict[str, np.ndarray], first_line: int, increasing: str | None, named: list[str]
) -> dict[str, np.ndarray]:
    """The columns of rows read at once, with what the row-by-row reader checks and repairs:
    `increasing` must not decrease, and rows repeating its value before them are merged into
    one sample (their mean) with a warning. Row i is on line first_line + i; `named`: the
    columns as the file names them."""
    if increasing is not None:
        stamps = columns[increasing]
        step = np.diff(stamps)
        back = np.flatnonzero(step < 0)
        if back.size:
            row = int(back[0]) + 1
            order = list(columns).index(increasing)
            raise ExperimentError(
                f"{path}:{first_line + row}: column {order + 1} ({named[order]}) = {float(stamps[row])} "
                "does not increase"
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
