"""The writers: a measured series to CSV (at once, or block by block as it is computed) and an
experiment to its TOML and CSV, in the format the readers read back. Columns come in SI and are
written in their file's units (:func:`pamkit.io.columns.to_file`): gauge_pressure_Pa as
pressure_kPa, temperature_K as temperature_C."""

from __future__ import annotations

import csv
import json
import math
import numbers
import re
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from pamkit.io.columns import file_name, file_unit, si_name, value_from_si
from pamkit.io.schema import EXPERIMENT_SECTIONS, TEST_KEYS

#: Rows formatted at a time by write_series.
WRITE_BLOCK_ROWS = 1 << 16


def write_series(path: str | Path, columns: dict[str, np.ndarray], digits: int = 10) -> None:
    """Writes SI columns of equal length to CSV, in their file units, with a header row of their
    file names, `digits` significant digits."""
    series = {name: np.asarray(column, dtype=float) for name, column in columns.items()}
    rows = len(next(iter(series.values()))) if series else 0
    with SeriesWriter(path, list(series), digits) as writer:
        # In blocks of rows, so that a long test's text never stands in memory whole.
        for start in range(0, rows, WRITE_BLOCK_ROWS):
            writer.write({name: column[start : start + WRITE_BLOCK_ROWS] for name, column in series.items()})


class SeriesWriter:
    """Writes a CSV block of rows by block, as they are computed, in write_series's format (the
    same bytes): a header row of the file names of `names` (SI column names), then their values
    in the file's units, `digits` significant digits ("%g"), csv's line ends (CRLF). A context
    manager; a failure inside it removes the partial file, so that a simulation that stops
    half-way leaves no CSV to mistake for its result.

        with SeriesWriter("out.csv", ["time_s", "gauge_pressure_Pa"]) as writer:
            writer.write({"time_s": t, "gauge_pressure_Pa": p})  # as often as there are blocks
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
        csv.writer(self._handle).writerow([file_name(name) for name in self.names])
        return self

    def write(self, columns: Mapping[str, np.ndarray]) -> None:
        """Appends rows: `columns` holds each name's values for them (SI), all of one length."""
        block = np.column_stack([value_from_si(name, np.asarray(columns[name], dtype=float)) for name in self.names])
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
    """Writes an experiment in the format load_experiment reads: the TOML at `path` and, given
    `columns`, its CSV beside it with the same stem (:func:`write_series`), which ``[test] data``
    then names. The one writer of experiment files: ``pamkit align``, ``pamkit synth`` and the
    thesis's data use it.

    Args:
        sections: section name -> {key: value}, written in the order given; each section one of
            :data:`EXPERIMENT_SECTIONS`, and ``[test]``'s keys those :data:`TEST_KEYS` names.
            Values: bool, int, float (finite), str, or a list of those.
        columns: the measured series, SI (write_series); without them ``[test] data`` must be given.
        comments: lines written as ``# ...`` at the top.

    Returns:
        The CSV's path (the one ``[test] data`` names).

    Raises:
        ValueError: naming the section and key of a value TOML cannot hold or the reader would refuse;
            naming a column given under its file's name (pressure_kPa) rather than its SI one.
    """
    path = Path(path)
    for name in columns or {}:
        if si_name(name) != name:
            raise ValueError(
                f"{path}: column {name} is its name in a file; columns are given in SI: "
                f"{si_name(name)} (written to the file as {name}, in {file_unit(si_name(name))})"
            )
    sections = {name: dict(table) for name, table in sections.items()}
    for name in sections:
        if name not in EXPERIMENT_SECTIONS:
            known = ", ".join(EXPERIMENT_SECTIONS)
            raise ValueError(f"{path}: cannot write section [{name}] (an experiment has {known})")
    test = sections.setdefault("test", {})
    if columns is not None:
        data = path.with_suffix(".csv")
        test.pop("data", None)
        test["data"] = data.name  # last, where a reader of the file looks for what it names
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
