"""The test a report asks for, written out for the lab: where one time series cannot tell two
explanations apart (a tie), names a cause only narrowly ahead of a rival, or refuses an
instrument's error as not needed, the report names the variant of the test on which they differ
most (separate.py). Here that variant becomes an experiment file the lab runs and completes:

- ``NEXT.toml``: the test's own sections with ``[test]`` changed as the variant says (the
  inflation pressure, for a sealed test; ``initial_length_m`` left for the lab to measure again,
  since the muscle seals at another length);
- ``NEXT.csv``: the motion to run (time_s, elongation_m; a supplied test's pressure too, scaled),
  which the lab's export of what it measured then replaces;
- ``NEXT.predictions.csv``: what each of the two explanations predicts that test will measure,
  in the file's units, to compare with on the spot.

Diagnosed together with the first (``pamkit diagnose FIRST.toml NEXT.toml``), the campaign names
the explanation that holds on both. A zero run has no motion: only the predictions are written
(what each explanation expects the instruments to read vented and unloaded), and the run goes to
the first test's ``[test] zero``."""

from __future__ import annotations

import csv
import os
from pathlib import Path

import numpy as np

from pamkit._core import GasMode, Measurement
from pamkit.diagnosis.series.separate import Separation
from pamkit.io.columns import file_name, value_from_si
from pamkit.io.experiment import Experiment, load_experiment
from pamkit.io.guards import read_toml
from pamkit.io.writers import write_experiment

# [test] keys that describe the first test's file and not the test: the new file is written here.
FILE_KEYS = ("data", "specimen", "ignore_columns", "description")
PREDICTION_DIGITS = 10


def asked_for(separation: Separation | None) -> str | None:
    """Why no test is written for `separation` (None: one is): the report asks for none, or none of
    the variants the model could run tells the two explanations apart."""
    if separation is None:
        return "the report asks for no further test: no tie, no close rival, no instrument's error left unchecked"
    if not separation.separates:
        return (
            f"no variant of this test pamkit can run tells {separation.between[0]} from {separation.between[1]} "
            "(their predictions differ by less than the noise's rule on each)"
        )
    return None


def next_sections(experiment: Experiment, separation: Separation, next_path: Path) -> dict:
    """The first test's TOML sections as the variant changes them, for a file at `next_path`."""
    sections = read_toml(experiment.path, "experiment")
    test = {k: v for k, v in sections.pop("test").items() if k not in FILE_KEYS}
    described = separation.variant.describe(separation.declared_Pa)
    if "inflation_gauge_pressure_Pa" in described:
        test["inflation_pressure_kPa"] = float(
            f"{value_from_si('gauge_pressure_Pa', described['inflation_gauge_pressure_Pa']):.6g}"
        )
        # Inflated freely to another pressure, the muscle seals at another length: measured
        # again, it goes here; without it the model inflates the declared build itself.
        test.pop("initial_length_m", None)
    if "zero" in test:  # the rig's zero run, named from where the new file stands
        zero = Path(experiment.path).parent / str(test["zero"])
        test["zero"] = Path(os.path.relpath(zero, next_path.parent)).as_posix()
    test["description"] = f"the test the diagnosis of {Path(experiment.path).name} asks for: {separation.test_phrase()}"
    return {**sections, "test": test}


def motion(experiment: Experiment, separation: Separation) -> dict[str, np.ndarray]:
    """The motion the lab runs (SI): the first test's, its times scaled; a supplied test's pressure
    scaled as the variant says."""
    described = separation.variant.describe(separation.declared_Pa)
    columns = {
        "time_s": np.asarray(experiment.time_s) * described.get("time_scale", 1.0),
        "elongation_m": np.asarray(experiment.elongation_m),
    }
    if experiment.gas == GasMode.supplied:
        columns["gauge_pressure_Pa"] = experiment.columns["gauge_pressure_Pa"] * described.get("pressure_scale", 1.0)
    return columns


def write_predictions(path: Path, separation: Separation, channels: tuple[str, ...]) -> None:
    """Each explanation's prediction of the variant, channel by channel, in the file's units: a
    column ``force_N [dead_volume]`` per channel and explanation, beside the time and elongation."""
    runs: tuple[Measurement, Measurement] = separation.predictions
    header = [file_name("time_s"), file_name("elongation_m")]
    values = [np.asarray(runs[0].time_s), np.asarray(runs[0].elongation_m)]
    for channel in channels:
        for name, run in zip(separation.between, runs):
            header.append(f"{file_name(channel)} [{name}]")
            values.append(value_from_si(channel, np.asarray(getattr(run, channel), dtype=float)))
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(header)
        for row in np.column_stack(values):
            writer.writerow([f"{v:.{PREDICTION_DIGITS}g}" for v in row])


def write_next_test(d, path) -> list[Path]:
    """Writes the test the report of `d` (one time series' diagnosis) asks for at `path`
    (NEXT.toml), its motion beside it and each explanation's prediction; for a zero run, the
    predictions only (module docstring). Returns the paths written.

    Raises:
        ValueError: for another kind of diagnosis (a campaign, a table), where the report asks for
            no test, or where none it could run separates the two explanations (asked_for).
    """
    separation = getattr(d, "separation", None)
    if not hasattr(d, "problem"):
        raise ValueError("one time series' report names the test to run next; a campaign's or a table's names none")
    why = asked_for(separation)
    if why is not None:
        raise ValueError(why)
    experiment = d.problem.experiment
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    predictions = path.with_suffix(".predictions.csv")
    write_predictions(predictions, separation, d.problem.channels)
    if separation.variant.zero_reading:
        return [predictions]
    first = load_experiment(experiment.path)  # every row: a long test is thinned for its diagnosis
    a, b = separation.between
    comments = [
        f"Written by pamkit diagnose --next-test: {separation.test_phrase()}.",
        f"Run it on the muscle and rig of {experiment.path}, replace {path.with_suffix('.csv').name} with what the "
        "instruments read (the same columns as that test's data),",
        f"and diagnose both together: pamkit diagnose {experiment.path} {path}",
        f"{predictions.name} holds what {a} and {b} each predict it will measure.",
    ]
    data = write_experiment(path, next_sections(first, separation, path), motion(first, separation), comments)
    return [path, data, predictions]
