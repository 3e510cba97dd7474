"""Reading a CSV of numbers under a header row, as every data file of pamkit's is: the header found
past comment lines (``#`` first) and blank ones, its names as pamkit's files spell them (another
unit's, or a spreadsheet's "Pressure [kPa]"), the delimiter and decimal mark from it. A plain file
is read in blocks by numpy; anything else, or a file with an error to name, row by row with the
csv module. Every problem is an :class:`~pamkit.io.guards.ExperimentError` naming the file, line
and column; a repair (a cut last line, repeated time stamps, rows missing a value) an
:class:`~pamkit.io.guards.ExperimentWarning` saying what was done. What each kind of test reads is
series.py's."""

from __future__ import annotations

import csv
import io
import math
import re
import warnings
from pathlib import Path

import numpy as np

from pamkit.io.columns import in_pamkit_units, other_units_of, pamkit_spelling, with_units_row
from pamkit.io.guards import (
    MAX_LINE_BYTES,
    ExperimentError,
    ExperimentWarning,
    checked_size,
    ends_unterminated,
    has_long_line,
    read_text,
)
from pamkit.io.missing import MISSING_CELLS, merged_sample, without_missing


def header_of(path: Path, ignore: tuple[str, ...] = ()) -> tuple[int, list[str]]:
    """The header's line number and names as pamkit's files name them (length_m for a file's
    length_mm), but those in `ignore` (as the file names them). Only the file's first SNIFF_BYTES
    are read (a record may be large): a file that cannot be read gives no names, and its reader
    says why."""
    try:
        if not path.is_file():  # a folder, a pipe that would block: the reader refuses it
            return 1, []
        with path.open("rb") as handle:
            head = handle.read(SNIFF_BYTES).decode("utf-8-sig", errors="replace")
    except OSError:
        return 1, []
    line, header = header_line(head)
    delimiter = delimiter_of(header)
    cells = next(csv.reader([header], delimiter=delimiter), [])
    below = _LINE_END.split(head)[line:]
    units = next((text for text in below if not _is_skipped(text)), None)
    completed = with_units_row(cells, next(csv.reader([units], delimiter=delimiter), [])) if units else None
    return line, [
        in_pamkit_units(pamkit_spelling(spelled))[0]
        for name, spelled in zip(cells, completed or cells)
        if name.strip() not in ignore
    ]


#: Bytes read to find a file's header line past its comment lines.
SNIFF_BYTES = 64 << 10

# A comment line: "#" first (after spaces or a byte-order mark), as a logger or a rig's software
# notes the date, the operator or a valve's switching. Its line end stays: lines keep their numbers.
_COMMENT_LINE = re.compile(r"(?:^|(?<=[\r\n]))[ \t\ufeff]*#[^\r\n]*")


def _is_skipped(line: str) -> bool:
    """Whether a line before the header is skipped: blank, or a comment."""
    stripped = line.strip(" \t\ufeff\r\n")
    return not stripped or stripped.startswith("#")


_LINE_END = re.compile(r"\r\n|[\r\n]")


def header_line(text: str) -> tuple[int, str]:
    """The header's line number (from 1) and text: the first line neither blank nor a comment (the
    first line if every one is). Lines end at LF, CR LF or a bare CR (an old Mac's or a logger's
    line end, which the csv module refuses inside a line). Only the lines up to the header are
    looked at: the text may be a large file's."""
    number, start = 1, 0
    for end in _LINE_END.finditer(text):
        if not _is_skipped(text[start : end.start()]):
            return number, text[start : end.start()]
        number, start = number + 1, end.end()
    if not _is_skipped(text[start:]):
        return number, text[start:]
    first = _LINE_END.search(text)
    return 1, text[: first.start()] if first else text


def delimiter_of(first_line: str) -> str:
    """The CSV's delimiter, from its header: European spreadsheets write "time_s;force_N" (and
    decimal commas), some machines tabs."""
    if ";" in first_line and "," not in first_line:
        return ";"
    return "\t" if "\t" in first_line else ","


def read_columns(
    path: Path,
    required: tuple[str, ...],
    optional: tuple[str, ...],
    increasing: str | None,
    ignore: tuple[str, ...] = (),
) -> dict[str, np.ndarray]:
    """The columns of a CSV: `required` ones and any of `optional`, `increasing` (if given) not
    decreasing, rows repeating it merged. A plain file is read in blocks by numpy; any other, or
    one with an error to name, row by row with the csv module. Columns named in `ignore` (as the
    file names them) are not read."""
    columns = _read_plain_csv(path, required, optional, increasing, ignore)
    if columns is not None:
        return columns
    text = read_text(path, "data")
    delimiter = delimiter_of(header_line(text)[1])
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
        header_number = reader.line_num
        rows = [(reader.line_num, row) for row in reader]
        # A line of units under the names (a logger's "Time, Force" over "s, N") completes them.
        first = next((i for i, (_, row) in enumerate(rows) if any(cell.strip() for cell in row)), None)
        completed = with_units_row(cells, rows[first][1]) if first is not None else None
        names = cells  # as the file names them, without the units: what [test] ignore_columns may say
        if completed is not None:
            cells = completed
            del rows[first]
        width = len(cells)
        # A column with no name (a spreadsheet's trailing delimiter on every line) is read only to
        # check that it holds nothing.
        unnamed = [number for number, cell in enumerate(cells) if not cell.strip()]
        kept = [
            number
            for number, (cell, name) in enumerate(zip(cells, names))
            if cell.strip() and cell.strip() not in ignore and name.strip() not in ignore
        ]
        cells = [cells[number] for number in kept]
        header, factors = _checked_header(path, header_number, cells, required, optional, numbers=kept)
        named = [cell.strip() for cell in cells]  # as the file names them, for its errors
        order = header.index(increasing) if increasing else None
    cut_last_line = ends_unterminated(path)
    values: list[list[float]] = []
    lines: list[int] = []  # each value row's line
    merged: list[int] = []  # lines whose time stamp repeated the one before
    weight: list[list[int]] = []  # rows averaged into each value row, column by column (a missing value is not one)
    for position, (line, row) in enumerate(rows):
        if not row or all(not cell.strip() for cell in row):
            continue
        try:
            if len(row) != width:
                raise ExperimentError(f"{path}:{line}: {len(row)} values, the header has {width}")
            for number in unnamed:
                if row[number].strip():
                    raise ExperimentError(
                        f"{path}:{line}: column {number + 1} has no name in the header but holds "
                        f"{_shown(row[number].strip())}: name it in the header (and in [test] ignore_columns to "
                        "leave it out)"
                    )
            row = [row[number] for number in kept]
            parsed = _parse_row(
                path, line, named, [c.replace(",", ".") for c in row] if decimal_comma else row, numbers=kept
            )
            if cut_last_line and position == len(rows) - 1 and any(math.isnan(value) for value in parsed):
                raise ExperimentError(f"{path}:{line}: a value is missing")
        except ExperimentError as error:
            if cut_last_line and position == len(rows) - 1:
                # A recording cut mid-line (a killed logger, a pulled cable): keep what came whole.
                warnings.warn(f"{path}:{line}: the last line is cut off ({error}); dropped", ExperimentWarning, 2)
                continue
            raise
        if order is not None and math.isnan(parsed[order]):
            raise ExperimentError(
                f"{path}:{line}: column {kept[order] + 1} ({named[order]}) has no value: every row needs its time"
            )
        if order is not None and values and parsed[order] == values[-1][order]:
            # A repeated stamp (a logger's clock resolution): one sample, the mean of the rows' values.
            values[-1], weight[-1] = merged_sample(values[-1], weight[-1], parsed)
            values[-1][order] = parsed[order]  # the mean of equal stamps, kept exact against the next one
            merged.append(line)
            continue
        if order is not None and values and parsed[order] < values[-1][order]:
            raise ExperimentError(
                f"{path}:{line}: column {order + 1} ({named[order]}) = {parsed[order]} does not increase"
            )
        values.append(parsed)
        lines.append(line)
        weight.append([0 if math.isnan(value) else 1 for value in parsed])
    if merged:
        warnings.warn(
            f"{path}:{merged[0]}: {len(merged)} row(s) repeat the time stamp before them (first at line {merged[0]}); "
            "each is merged with it into one sample (their mean)",
            ExperimentWarning,
            2,
        )
    table = np.asarray(values, dtype=float).reshape(len(values), len(header))
    columns = {name: table[:, index].copy() for index, name in enumerate(header)}
    columns = without_missing(path, columns, lines.__getitem__, named, required, kept)
    _check_rows(path, columns)
    return _in_pamkit_units(columns, dict(zip(header, factors)))


def _check_rows(path: Path, columns: dict[str, np.ndarray]) -> None:
    rows = len(next(iter(columns.values())))
    if rows < 2:
        raise ExperimentError(f"{path}: needs at least 2 data rows, found {rows}")


def _shown(cell: str, limit: int = 40) -> str:
    """A cell as a message quotes it: on one line (a quoted cell may hold line ends), escaped
    where not printable (a stray byte-order mark), shortened past `limit` characters."""
    return repr(cell if len(cell) <= limit else cell[:limit] + "...")


def _checked_header(
    path: Path,
    line: int,
    cells: list[str],
    required: tuple[str, ...],
    optional: tuple[str, ...],
    numbers: list[int] | None = None,
) -> tuple[list[str], list[float]]:
    """The header's channel names (on line `line`) as pamkit's files name them, each known and
    given once, the required ones all there; and the factor that takes each column to that name's
    unit (a column in another unit, OTHER_UNITS: length_mm is length_m, 0.001). `numbers`: each
    cell's column in the file, from 0 (where ignored ones were taken out)."""
    known = required + optional
    header, factors = [], []
    for index, cell in enumerate(cells):
        number = (numbers[index] if numbers is not None else index) + 1
        name, factor = in_pamkit_units(pamkit_spelling(cell))
        if name not in known:
            others = other_units_of(known)
            raise ExperimentError(
                f"{path}:{line}: column {number} {_shown(cell.strip())} is not a known channel ({', '.join(known)}"
                + (f"; or in other units: {', '.join(others)}" if others else "")
                + "; a column not to read is named in [test] ignore_columns)"
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


def _in_pamkit_units(columns: dict[str, np.ndarray], factors: dict[str, float]) -> dict[str, np.ndarray]:
    """Each column times its factor from _checked_header, where it is not 1."""
    return {name: values * factors[name] if factors[name] != 1.0 else values for name, values in columns.items()}


#: Bytes of a data file numpy parses at a time (then to the end of the line): the file's text
#: never stands in memory whole, only one block of it beside the numbers read so far.
READ_BLOCK_BYTES = 4 << 20


def _read_plain_csv(
    path: Path,
    required: tuple[str, ...],
    optional: tuple[str, ...],
    increasing: str | None,
    ignore: tuple[str, ...] = (),
) -> dict[str, np.ndarray] | None:
    """The columns of a plain CSV, read block by block (READ_BLOCK_BYTES) by numpy: a 2-million-row
    file (108 MB) in 80 MB, its numbers, where its bytes, text and numbers at once took 4.5 times
    the file. None when the file is not plain throughout: a quoted cell, a bare carriage return,
    a blank line (numpy skips it, and rows would no longer be lines), a cell numpy does not read
    as a finite number or a missing one (NaN, or empty), a row of empty cells, a row of another
    width, text that is not UTF-8, a line over
    MAX_LINE_BYTES, no data row, or a file that cannot be opened. The caller then reads its
    whole text row by row, which names the first problem's line and column. A cut last line
    (no line end: a killed logger) is parsed on its own and, as row by row, dropped with a
    warning unless it is a whole row. The header is checked after the rows, as the whole-text
    reader's order of errors has it (a file that cannot be decoded is named as such first)."""
    limit = checked_size(path, "data")
    try:
        with path.open("rb") as handle:
            before = header_number = 0  # bytes and lines up to the header's end
            header_text = ""
            while _is_skipped(header_text):
                first = handle.readline(MAX_LINE_BYTES + 1)
                try:
                    header_text = first.decode("utf-8-sig" if not before else "utf-8")
                except UnicodeDecodeError:
                    return None
                if not header_text.endswith("\n") or not _is_plain(header_text):
                    return None
                before += len(first)
                header_number += 1
            delimiter = delimiter_of(header_text)
            cells = next(csv.reader([header_text[:-1]], delimiter=delimiter))
            if any(cell.strip() in ignore or not cell.strip() for cell in cells):
                return None  # a column not to read, or one with no name: row by row, which leaves it out
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
            if any(math.isnan(value) for value in values):
                raise ExperimentError(f"{path}:{line}: a value is missing")
        except ExperimentError as error:
            warnings.warn(f"{path}:{line}: the last line is cut off ({error}); dropped", ExperimentWarning, 3)
        else:
            for column, value in zip(columns, values):
                column[rows_read] = value
            rows_read += 1
    for column in columns:
        column.resize(rows_read, refcheck=False)  # in place: nothing else refers to it
    checked = _checked_columns(path, dict(zip(header, columns)), header_number + 1, increasing, named, required)
    return _in_pamkit_units(checked, dict(zip(header, factors)))


def _is_plain(text: str) -> bool:
    """No quoted cell (numpy's reader does not unquote), no carriage return but before a line feed."""
    return '"' not in text and text.count("\r") == text.count("\r\n")


def _parse_block(text: str, delimiter: str, width: int) -> np.ndarray | None:
    """Whole lines of numbers parsed by numpy (10^6 rows in about 1.5 s of CPU, where the csv
    module and float() take ten times that): one row a line, `width` numbers each, finite or
    missing (NaN, or an empty cell: read as NaN), or None."""
    if delimiter != ",":  # decimal commas
        text = text.replace(",", ".")
    if _has_empty_cell(text, delimiter):
        text = re.sub(rf"(?m)(^|{re.escape(delimiter)})[ \t]*(?={re.escape(delimiter)}|\r?\n)", r"\1nan", text)
    try:
        # Bytes, not a StringIO: numpy reads them in chunks, a StringIO would hold 4 bytes a character.
        rows = np.loadtxt(
            io.BytesIO(text.encode()), delimiter=delimiter, dtype=float, ndmin=2, comments=None, encoding="utf-8"
        )
    except ValueError:
        return None
    if rows.shape != (text.count("\n"), width) or np.isinf(rows).any() or np.isnan(rows).all(axis=1).any():
        return None  # a row of empty cells is a blank line to the row-by-row reader
    return rows


def _has_empty_cell(text: str, delimiter: str) -> bool:
    """Whether a line of `text` (whole lines) has an empty cell: substring scans, which a block
    without one costs next to nothing."""
    return text.startswith(delimiter) or any(
        pair in text for pair in (delimiter * 2, "\n" + delimiter, delimiter + "\n", delimiter + "\r")
    )


def _checked_columns(
    path: Path,
    columns: dict[str, np.ndarray],
    first_line: int,
    increasing: str | None,
    named: list[str],
    required: tuple[str, ...],
) -> dict[str, np.ndarray]:
    """The columns of rows read at once, with what the row-by-row reader checks and repairs:
    `increasing` must not decrease, nor be missing, and rows repeating its value before them are
    merged into one sample (each column the mean of the values it has) with a warning; rows
    missing a value are left out (missing.without_missing). Row i is on line first_line + i;
    `named`: the columns as the file names them."""
    starts = None  # the rows that begin each sample, where rows were merged
    if increasing is not None:
        stamps = columns[increasing]
        order = list(columns).index(increasing)
        if np.isnan(stamps).any():
            line = first_line + int(np.argmax(np.isnan(stamps)))
            raise ExperimentError(
                f"{path}:{line}: column {order + 1} ({named[order]}) has no value: every row needs its time"
            )
        step = np.diff(stamps)
        back = np.flatnonzero(step < 0)
        if back.size:
            row = int(back[0]) + 1
            raise ExperimentError(
                f"{path}:{first_line + row}: column {order + 1} ({named[order]}) = {float(stamps[row])} "
                "does not increase"
            )
        repeats = np.flatnonzero(step == 0) + 1
        if repeats.size:
            starts = np.flatnonzero(np.concatenate([[True], step != 0]))
            columns = {name: _means_at(column, starts) for name, column in columns.items()}
            first = first_line + int(repeats[0])
            warnings.warn(
                f"{path}:{first}: {repeats.size} row(s) repeat the time stamp before them (first at line {first}); "
                "each is merged with it into one sample (their mean)",
                ExperimentWarning,
                4,
            )
    columns = without_missing(
        path, columns, lambda row: first_line + (row if starts is None else int(starts[row])), named, required
    )
    _check_rows(path, columns)
    return columns


def _means_at(column: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """The means of the column's runs that begin at `starts`, of the values each has (NaN where
    it has none)."""
    missing = np.isnan(column)
    if not missing.any():
        return np.add.reduceat(column, starts) / np.diff(np.append(starts, column.size))
    sums = np.add.reduceat(np.where(missing, 0.0, column), starts)
    counts = np.add.reduceat(~missing, starts)
    return np.divide(sums, counts, out=np.full(sums.shape, np.nan), where=counts > 0)


def _parse_row(
    path: Path, line: int, header: list[str], row: list[str], numbers: list[int] | None = None
) -> list[float]:
    """A row's cells as numbers, NaN for a missing one (MISSING_CELLS); `numbers`: each cell's
    column in the file, from 0 (where ignored ones were taken out)."""
    if len(row) != len(header):
        raise ExperimentError(f"{path}:{line}: {len(row)} values, the header has {len(header)}")
    parsed = []
    for index, (name, cell) in enumerate(zip(header, row)):
        column = (numbers[index] if numbers is not None else index) + 1
        if cell.strip().lower() in MISSING_CELLS:
            parsed.append(math.nan)
            continue
        try:
            value = float(cell)
        except ValueError:
            raise ExperimentError(
                f"{path}:{line}: column {column} ({name}) = {cell.strip()!r} is not a number"
            ) from None
        if math.isnan(value):
            parsed.append(math.nan)
            continue
        if not math.isfinite(value):
            raise ExperimentError(f"{path}:{line}: column {column} ({name}) = {cell.strip()!r} is not finite")
        parsed.append(value)
    return parsed
