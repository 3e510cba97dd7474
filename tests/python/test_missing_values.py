"""Values a data file does not have (a sensor's dropout, a logger's empty cell, a spreadsheet's
NaN): a row missing one is left out whole, said where, and kept in the report; what cannot be
read so is refused naming the column and line."""

import json
import shutil

import numpy as np
import pytest
from conftest import SOURCE_DIR

import pamkit
import pamkit.io.csv_reader as csv_reader
from pamkit.diagnosis.batch import diagnose_file
from pamkit.io.experiment import load_experiment
from pamkit.io.guards import ExperimentError, ExperimentWarning
from pamkit.io.series import read_series

EXAMPLE = SOURCE_DIR / "data" / "experiments" / "example"
ISOTONIC = SOURCE_DIR / "data" / "experiments" / "isotonic"

WHOLE = "time_s,elongation_m,force_N,pressure_kPa\n0,0,1,100\n1,0.001,2,101\n2,0.002,3,102\n3,0.003,4,103\n"


def test_rows_missing_a_value_are_left_out_with_a_warning_naming_them(tmp_path):
    path = tmp_path / "run.csv"
    # Each spelling of a missing value: an empty cell, NaN, NA, as loggers and data frames write them.
    path.write_text(
        "time_s,elongation_m,force_N,pressure_kPa\n0,0,1,100\n1,0.001,,101\n2,0.002,3,102\n"
        "3,0.003,NaN,NA\n4,0.004,5,104\n5,0.005,6,105\n6,0.006,7,106\n"
    )
    with pytest.warns(
        ExperimentWarning,
        match=r"run.csv:3: 2 row\(s\) miss a value \(first at line 3; force_N in 2, pressure_kPa in 1\); each is left "
        r"out whole",
    ):
        columns = read_series(path)
    np.testing.assert_array_equal(columns["time_s"], [0, 2, 4, 5, 6])
    np.testing.assert_array_equal(columns["force_N"], [1, 3, 5, 6, 7])


def test_a_column_with_no_value_in_any_row_is_not_measured_unless_required(tmp_path):
    path = tmp_path / "run.csv"
    path.write_text("time_s,elongation_m,force_N,temperature_C\n0,0,1,\n1,0.001,2,\n2,0.002,3,\n")
    with pytest.warns(ExperimentWarning, match=r"column 4 \(temperature_C\) has no value in any row: read as not"):
        columns = read_series(path)
    assert sorted(columns) == ["elongation_m", "force_N", "time_s"]
    path.write_text("time_s,elongation_m,force_N\n0,,1\n1,,2\n")
    with pytest.raises(ExperimentError, match=r"run.csv: column 2 \(elongation_m\) has no value in any row"):
        read_series(path)


def test_a_channel_missing_in_most_rows_is_refused_as_one_logged_at_another_rate(tmp_path):
    # A thermometer logged once a second beside a 10 Hz load cell: leaving out the rows without it
    # would thin every channel to its rate.
    rows = [f"{k / 10},{k * 1e-4},{k},{20 + k / 100 if k % 10 == 0 else ''}" for k in range(30)]
    path = tmp_path / "run.csv"
    path.write_text("time_s,elongation_m,force_N,temperature_C\n" + "\n".join(rows) + "\n")
    with pytest.raises(
        ExperimentError,
        match=r"run.csv:3: column 4 \(temperature_C\) has no value in 27 of 30 rows \(a channel logged at another "
        r"rate\?\).*or leave it out with \[test\] ignore_columns",
    ):
        read_series(path)


def test_a_row_without_its_time_is_refused(tmp_path):
    path = tmp_path / "run.csv"
    path.write_text(WHOLE.replace("\n2,", "\n,"))
    with pytest.raises(ExperimentError, match=r"run.csv:4: column 1 \(time_s\) has no value: every row needs its time"):
        read_series(path)


def test_rows_that_repeat_a_time_stamp_merge_the_values_they_have(tmp_path):
    path = tmp_path / "run.csv"
    path.write_text(WHOLE.replace("1,0.001,2,101\n", "1,0.001,2,\n1,0.003,4,105\n"))
    with pytest.warns(ExperimentWarning, match="repeat the time stamp"):
        columns = read_series(path)
    # The force is the mean of both rows', the pressure the one row's that has it.
    assert columns["force_N"][1] == pytest.approx(3.0) and columns["gauge_pressure_Pa"][1] == pytest.approx(105e3)


def test_a_cut_last_line_missing_values_is_dropped_as_cut(tmp_path):
    path = tmp_path / "run.csv"
    path.write_text(WHOLE + "4,0.004,")  # the logger stopped mid-line
    with pytest.warns(ExperimentWarning, match=r"run.csv:6: the last line is cut off"):
        columns = read_series(path)
    assert list(columns["time_s"]) == [0, 1, 2, 3]


def test_a_table_row_missing_its_length_is_left_out_and_the_experiment_keeps_the_warning(tmp_path):
    for name in ("isotonic.toml", "isotonic.csv"):
        shutil.copy(ISOTONIC / name, tmp_path / name)
    lines = (tmp_path / "isotonic.csv").read_text().splitlines()
    lines[5] = lines[5].split(",")[0] + ","  # line 6: the laser lost the target
    (tmp_path / "isotonic.csv").write_text("\n".join(lines) + "\n")
    whole = load_experiment(ISOTONIC / "isotonic.toml")
    with pytest.warns(ExperimentWarning, match=r"isotonic.csv:6: 1 row\(s\) miss a value"):
        gapped = load_experiment(tmp_path / "isotonic.toml")
    for name, values in whole.columns.items():
        np.testing.assert_array_equal(gapped.columns[name], np.delete(values, 4))  # row 5, on line 6
    assert len(gapped.data_warnings) == 1 and "isotonic.csv:6" in gapped.data_warnings[0]
    assert whole.data_warnings == []


def _with_dropouts(source, target, seed, share=0.01):
    """The example's CSV with `share` of its force and of its pressure cells emptied at random."""
    rng = np.random.default_rng(seed)
    lines = source.read_text().splitlines()
    for index in range(1, len(lines)):
        cells = lines[index].split(",")
        for column in (2, 3):  # force_N, pressure_kPa
            if rng.random() < share:
                cells[column] = "" if column == 2 else "NaN"
        lines[index] = ",".join(cells)
    target.write_text("\n".join(lines) + "\n")


def test_a_diagnosis_with_dropouts_names_what_it_names_without_and_reports_them(tmp_path):
    # The bundled example (a heat transfer hidden in a bench test) with 1 % of its force and of its
    # pressure samples lost, three ways: the verdict is the whole file's in each (the measure: the
    # same diagnosis on every row), the gain within 0.005 of it, and the report says what was left out.
    whole = pamkit.diagnose(EXAMPLE / "experiment.toml", threads=2).to_dict()
    named = 0
    for seed in range(3):
        (tmp_path / "experiment.toml").write_text((EXAMPLE / "experiment.toml").read_text())
        _with_dropouts(EXAMPLE / "experiment.csv", tmp_path / "experiment.csv", seed)
        with pytest.warns(ExperimentWarning, match="miss a value"):
            report = json.loads(json.dumps(pamkit.diagnose(tmp_path / "experiment.toml", threads=2).to_dict()))
        left_out = [w["reading"] for w in report["warnings"] if "reading" in w]
        assert len(left_out) == 1 and "each is left out whole" in left_out[0]
        if report["cause"] == whole["cause"]:
            gain = {c: abs(report["gain"][c] - whole["gain"][c]) for c in whole["gain"]}
            named += max(gain.values()) < 0.005
    assert named == 3


def test_a_batch_row_counts_what_reading_said_once(tmp_path):
    # The report holds what reading the data said, and Python warned of it too: one warning.
    (tmp_path / "experiment.toml").write_text((EXAMPLE / "experiment.toml").read_text())
    _with_dropouts(EXAMPLE / "experiment.csv", tmp_path / "experiment.csv", seed=0)
    whole = diagnose_file(EXAMPLE / "experiment.toml")
    with pytest.warns(ExperimentWarning, match="miss a value"):
        report = pamkit.diagnose(tmp_path / "experiment.toml", threads=1).to_dict()
    row = diagnose_file(tmp_path / "experiment.toml")
    assert row["warnings"] == len(report["warnings"]) == whole["warnings"] + 1


@pytest.mark.parametrize("block", [100, 1 << 20])
def test_a_plain_file_with_dropouts_reads_in_blocks_as_row_by_row(tmp_path, monkeypatch, block):
    # A logger's rows with repeated stamps and 2 % of each channel's cells missing (empty or NaN),
    # in blocks that end mid-row or in one; quoted names send the same rows to the row-by-row
    # reader, the reference: the same columns and the same warnings.
    rng = np.random.default_rng(5)
    count = 2000
    stamps = np.cumsum(rng.choice([0, 1, 1, 1], size=count)) * 1e-3
    table = np.column_stack([stamps, rng.uniform(0, 0.05, count), rng.normal(100, 30, (count, 2))])
    cells = [[f"{v:.10g}" for v in row] for row in table]
    for row in cells:
        for column in (1, 2, 3):
            if rng.random() < 0.02:
                row[column] = "" if rng.random() < 0.5 else "NaN"
    body = "".join(",".join(row) + "\n" for row in cells)
    plain, quoted = tmp_path / "plain.csv", tmp_path / "quoted.csv"
    plain.write_text("time_s,elongation_m,force_N,pressure_kPa\n" + body)
    quoted.write_text('"time_s","elongation_m","force_N","pressure_kPa"\n' + body)
    with pytest.warns(ExperimentWarning) as whole:
        reference = read_series(quoted)
    monkeypatch.setattr(csv_reader, "READ_BLOCK_BYTES", block)
    monkeypatch.setattr(csv_reader, "read_text", lambda *_: pytest.fail("the plain file was read row by row"))
    with pytest.warns(ExperimentWarning) as in_blocks:
        blocks = read_series(plain)
    assert [str(w.message).replace("plain.csv", "quoted.csv") for w in in_blocks] == [str(w.message) for w in whole]
    assert any("miss a value" in str(w.message) for w in whole) and any("repeat" in str(w.message) for w in whole)
    assert list(blocks) == list(reference)
    for name in blocks:
        # Merged samples are means: a running mean row by row, one sum in blocks (rounding only).
        np.testing.assert_allclose(blocks[name], reference[name], rtol=1e-13, atol=0)
    assert not any(np.isnan(values).any() for values in blocks.values())
