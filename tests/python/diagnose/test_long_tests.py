"""Long tests (issue #14): a test over MAX_DIAGNOSED_ROWS is diagnosed on every k-th row and
says so (a warning, the report's warnings), and every phase of diagnosis reports progress."""

import math

import pytest

import pamkit.diagnose.engine as engine
from pamkit.diagnose import diagnose, to_json
from pamkit.experiment import load_experiment
from pamkit.synth import synthesize


@pytest.fixture(scope="module")
def leak_dataset(tmp_path_factory):
    # The leak test_diagnose.py names from every row (tau = 300 s, seed 5).
    return synthesize("leak:time_constant_s=300", 5, tmp_path_factory.mktemp("leak"))


def test_a_test_over_the_row_limit_is_thinned_says_so_and_keeps_its_cause(leak_dataset, monkeypatch):
    rows = load_experiment(leak_dataset.experiment).time_s.size
    monkeypatch.setattr(engine, "MAX_DIAGNOSED_ROWS", rows // 3)  # one row in 4 is the fewest that fits
    kept = math.ceil(rows / 4)
    messages = []
    with pytest.warns(engine.ThinningWarning, match=rf"{rows} rows, .*diagnosed on one row in 4 \({kept} rows"):
        d = diagnose(leak_dataset.experiment, progress=messages.append, threads=2)
    assert d.problem.experiment.time_s.size == kept
    notes = [w for w in to_json(d)["warnings"] if "thinned" in w]
    assert notes == [{"thinned": notes[0]["thinned"], "step": 4, "rows_read": rows, "rows_diagnosed": kept}]
    # The leak (peaks drifting down over minutes) is as plain at a quarter of the rate.
    assert d.cause == "leak"
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
    ]
    starts = [next(i for i, m in enumerate(messages) if m.startswith(p)) for p in phases]
    assert starts == sorted(starts)


def test_a_test_within_the_row_limit_keeps_every_row(leak_dataset):
    experiment = load_experiment(leak_dataset.experiment)
    same, note = engine.thinned(experiment, max_rows=experiment.time_s.size)
    assert same is experiment and note is None
