"""Long tests: a test over MAX_DIAGNOSED_ROWS is diagnosed on every k-th row and
says so (a one-line warning on stderr, the report's warnings), and every phase of diagnosis
reports its start on stderr."""

import json
import math
import re
import warnings

import pytest

import pamkit.diagnosis.engine as engine
from pamkit.cli import main
from pamkit.io.experiment import load_experiment
from pamkit.synth.dataset import synthesize


@pytest.fixture(scope="module")
def leak_dataset(tmp_path_factory):
    # The leak test_diagnose.py names from every row (tau = 300 s, seed 5).
    return synthesize("leak:time_constant_s=300", 5, tmp_path_factory.mktemp("leak"))


def test_a_test_over_the_row_limit_is_thinned_says_so_and_keeps_its_cause(leak_dataset, monkeypatch, tmp_path, capsys):
    rows = load_experiment(leak_dataset.experiment).time_s.size
    monkeypatch.setattr(engine, "MAX_DIAGNOSED_ROWS", rows // 3)  # one row in 4 is the fewest that fits
    kept = math.ceil(rows / 4)
    report = tmp_path / "report.json"
    with warnings.catch_warnings():
        warnings.simplefilter("always", engine.ThinningWarning)  # as outside pytest: shown, not raised
        assert main(["diagnose", str(leak_dataset.experiment), "--json", str(report), "--threads", "2"]) == 0
    err = capsys.readouterr().err.splitlines()
    said = rf"pamkit: warning: .*{rows} rows, .*diagnosed on one row in 4 \({kept} rows"
    assert [line for line in err if re.match(said, line)], err
    notes = [w for w in json.loads(report.read_text())["warnings"] if "thinned" in w]
    assert notes == [{"thinned": notes[0]["thinned"], "step": 4, "rows_read": rows, "rows_diagnosed": kept}]
    # The leak (peaks drifting down over minutes) is as plain at a quarter of the rate.
    assert json.loads(report.read_text())["cause"] == "leak"
    # Every phase says when it starts, in order.
    phases = [
        "reading",
        "read ",
        "finding the test's",
        "calibrating the baseline",
        "baseline calibrated in",
        "fitting ",
        "deciding",
        "cause: leak",
        "writing",
    ]
    starts = [next(i for i, line in enumerate(err) if line.strip().startswith(phase)) for phase in phases]
    assert starts == sorted(starts)


def test_a_test_within_the_row_limit_keeps_every_row(leak_dataset):
    experiment = load_experiment(leak_dataset.experiment)
    same, note = engine.thinned(experiment, max_rows=experiment.time_s.size)
    assert same is experiment and note is None
