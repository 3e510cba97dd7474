"""Values a data file does not have (a sensor's dropout, a logger's empty cell, a spreadsheet's
NaN): which cells say so, and what reading does with a row or a column that misses them.
csv_reader.py reads a missing cell as NaN and hands its table here."""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np

from pamkit.io.guards import ExperimentError, ExperimentWarning

#: Cells that say a value is missing (a dropout), as spreadsheets, loggers and data frames write
#: one, in any case; a NaN too. Such a value is NaN where it is read (read_columns leaves it out).
MISSING_CELLS = ("", "na", "n/a", "#n/a", "null", "none", "-")


def merged_sample(values: list[float], counts: list[int], row: list[float]) -> tuple[list[float], list[int]]:
    """A sample's values (each the mean of `counts` rows' values) with one more row's: column by
    column, a missing value (NaN) leaves the mean as it is."""
    merged, weights = [], []
    for value, count, new in zip(values, counts, row):
        if math.isnan(new):
            merged.append(value)
            weights.append(count)
        else:
            merged.append(new if not count else (count * value + new) / (count + 1))
            weights.append(count + 1)
    return merged, weights


#: The largest share of a file's rows a missing value may leave out: a channel missing in more is
#: a channel logged at another rate, which dropping rows would thin out to its own rate.
MOST_ROWS_MISSING = 0.5


def without_missing(
    path: Path,
    columns: dict[str, np.ndarray],
    line_of: Callable[[int], int],
    named: list[str],
    required: tuple[str, ...],
    numbers: list[int] | None = None,
) -> dict[str, np.ndarray]:
    """The columns without their missing values (NaN): a column missing in every row is not
    measured (an error if `required`), a row missing a value is left out whole (pamkit compares
    every channel at each sample) with a warning naming its first line and each column's count,
    and a column missing in more than MOST_ROWS_MISSING of the rows is an error. `line_of`: a
    row's line in the file; `named`: the columns as the file names them, in `columns`' order,
    `numbers` their columns in the file, from 0 (by default their order). A large file's columns
    are copied only where rows are left out, and looked at one at a time."""
    gappy = [name for name, values in columns.items() if np.isnan(values).any()]
    if not gappy:
        return columns
    file_name = dict(zip(columns, named))
    where = {
        name: f"column {(numbers[index] if numbers is not None else index) + 1} ({file_name[name]})"
        for index, name in enumerate(columns)
    }
    for name in [name for name in gappy if np.isnan(columns[name]).all()]:
        if name in required:
            raise ExperimentError(f"{path}: {where[name]} has no value in any row")
        warnings.warn(f"{path}: {where[name]} has no value in any row: read as not measured", ExperimentWarning, 3)
        del columns[name]
    counts = {name: int(np.isnan(columns[name]).sum()) for name in gappy if name in columns}
    if not counts:
        return columns
    rows = len(next(iter(columns.values())))
    worst = max(counts, key=lambda name: counts[name])
    if counts[worst] > MOST_ROWS_MISSING * rows:
        hint = "" if worst in required else ", or leave it out with [test] ignore_columns"
        raise ExperimentError(
            f"{path}:{line_of(int(np.argmax(np.isnan(columns[worst]))))}: {where[worst]} has no value in "
            f"{counts[worst]} of {rows} rows (a channel logged at another rate?): pamkit compares every channel at "
            f"each sample; give it a value in every row{hint}"
        )
    gaps = np.logical_or.reduce([np.isnan(columns[name]) for name in counts])
    first = line_of(int(np.argmax(gaps)))
    each = ", ".join(f"{file_name[name]} in {count}" for name, count in counts.items())
    warnings.warn(
        f"{path}:{first}: {int(gaps.sum())} row(s) miss a value (first at line {first}; {each}); each is left out "
        "whole, its other values unused (pamkit compares every channel at each sample)",
        ExperimentWarning,
        3,
    )
    return {name: values[~gaps] for name, values in columns.items()}
