"""Values a data file does not have (a sensor's dropout, a logger's empty cell, a spreadsheet's
NaN): which cells say so, and what reading does with a row or a column that misses them.
csv_reader.py reads a missing cell as NaN and hands its table here."""

from __future__ import annotations

import math
import warnings
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
    table: np.ndarray,
    lines: np.ndarray,
    header: list[str],
    factors: list[float],
    named: list[str],
    required: tuple[str, ...],
    numbers: list[int],
) -> tuple[np.ndarray, list[str], list[float]]:
    """The table without its missing values (MISSING_CELLS, NaN in `table`): a column missing in
    every row is not measured (an error if `required`), a row missing a value is left out whole
    (pamkit compares every channel at each sample) with a warning naming the lines, and a column
    missing in more than MOST_ROWS_MISSING of the rows is an error. `lines`: each row's line;
    `named`: the columns as the file names them, `numbers` their columns in the file, from 0."""
    missing = np.isnan(table)
    if not missing.any():
        return table, header, factors
    empty = [index for index in range(len(header)) if missing[:, index].all()]
    for index in empty:
        where = f"column {numbers[index] + 1} ({named[index]})"
        if header[index] in required:
            raise ExperimentError(f"{path}: {where} has no value in any row")
        warnings.warn(f"{path}: {where} has no value in any row: read as not measured", ExperimentWarning, 3)
    kept = [index for index in range(len(header)) if index not in empty]
    table, missing = table[:, kept], missing[:, kept]
    header, factors = [header[i] for i in kept], [factors[i] for i in kept]
    named, numbers = [named[i] for i in kept], [numbers[i] for i in kept]
    gaps = missing.any(axis=1)
    if not gaps.any():
        return table, header, factors
    counts = missing.sum(axis=0)
    worst = int(np.argmax(counts))
    if counts[worst] > MOST_ROWS_MISSING * len(table):
        hint = "" if header[worst] in required else ", or leave it out with [test] ignore_columns"
        raise ExperimentError(
            f"{path}:{int(lines[np.argmax(missing[:, worst])])}: column {numbers[worst] + 1} ({named[worst]}) has no "
            f"value in {int(counts[worst])} of {len(table)} rows (a channel logged at another rate?): pamkit compares "
            f"every channel at each sample; give it a value in every row{hint}"
        )
    first = int(lines[np.argmax(gaps)])
    each = ", ".join(f"{named[i]} in {int(counts[i])}" for i in np.flatnonzero(counts))
    warnings.warn(
        f"{path}:{first}: {int(gaps.sum())} row(s) miss a value (first at line {first}; {each}); each is left out "
        "whole, its other values unused (pamkit compares every channel at each sample)",
        ExperimentWarning,
        3,
    )
    return table[~gaps], header, factors
