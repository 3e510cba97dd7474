"""`pamkit diagnose --next-test`: the test a report asks for, written as an experiment file the lab
runs (series/next_test.py). Checked on the bundled tie (a dead volume one sealed test cannot tell
from stretching fibres): the file reads back as the variant of the first test the report names,
its motion is the first test's, and its predictions are the two explanations whose difference
the report measured."""

import csv
import json

import numpy as np
import pytest
from conftest import SOURCE_DIR

from pamkit import Report
from pamkit._core import GasMode
from pamkit.diagnosis import diagnose, verdict
from pamkit.diagnosis.report import to_json
from pamkit.diagnosis.series.next_test import asked_for, write_next_test
from pamkit.diagnosis.series.separate import SEPARATES, Separation, Variant, _differences
from pamkit.io.columns import value_from_si
from pamkit.io.experiment import load_experiment
from pamkit.simulation import simulate_experiment


@pytest.fixture(scope="module")
def tie():
    """The bundled tie's first test and its diagnosis (fiber_compliance and dead_volume tied)."""
    path = SOURCE_DIR / "data" / "experiments" / "tie" / "first" / "test.toml"
    return path, diagnose(path, threads=2)


def read_predictions(path):
    with path.open(newline="") as handle:
        rows = list(csv.reader(handle))
    return rows[0], np.array(rows[1:], dtype=float)


def test_the_tie_asks_for_another_inflation_and_the_file_is_that_test(tie, tmp_path, run_pamkit):
    path, d = tie
    assert d.separation is not None and d.separation.purpose == "tie"
    done = run_pamkit(
        "diagnose", path, "--quiet", "--json", tmp_path / "report.json", "--next-test", tmp_path / "next.toml"
    )
    assert done.returncode == 0, done.stderr
    for name in ("next.toml", "next.csv", "next.predictions.csv"):
        assert f"wrote {tmp_path / name}" in done.stdout
    report = json.loads((tmp_path / "report.json").read_text())
    asked = report["separation"]["test"]

    first, written = load_experiment(path), load_experiment(tmp_path / "next.toml")
    assert written.inflation_gauge_pressure_Pa == pytest.approx(asked["inflation_gauge_pressure_Pa"], rel=1e-5)
    assert written.initial_length_m is None  # sealed at another pressure, at another length: measured again
    assert written.build.to_dict() == first.build.to_dict()
    assert written.gas == first.gas
    np.testing.assert_allclose(written.time_s, first.time_s, rtol=1e-9)
    np.testing.assert_allclose(written.elongation_m, first.elongation_m, rtol=1e-9, atol=1e-15)
    assert set(written.columns) == {"time_s", "elongation_m"}  # the protocol: the lab's data replace it
    simulated = simulate_experiment(written)  # a protocol pamkit runs, as `pamkit simulate` would
    assert np.all(np.isfinite(simulated["force_N"]))

    # The predictions are the two explanations the report measured apart: their RMS difference over
    # the first test's noise is the report's, channel by channel.
    header, values = read_predictions(tmp_path / "next.predictions.csv")
    a, b = report["separation"]["between"]
    noise = report["evidence"]["noise"]
    for channel, file_column in (("force_N", "force_N"), ("gauge_pressure_Pa", "pressure_kPa")):
        difference = values[:, header.index(f"{file_column} [{a}]")] - values[:, header.index(f"{file_column} [{b}]")]
        in_noise = difference / value_from_si(channel, noise[channel])  # kPa and N: no offset to the unit
        apart = float(np.sqrt(np.mean(in_noise**2)))
        assert apart == pytest.approx(report["separation"]["difference_over_noise"][channel], rel=1e-6)
    # Inflated freely, each explanation's muscle starts carrying no force: the variant's start is
    # its own free length, compliant fibres included.
    force = [header.index(f"force_N [{name}]") for name in (a, b)]
    assert np.all(np.abs(values[0, force]) < 1e-6)


def written_as_if_asked(d, variant, path) -> list:
    """write_next_test for `d` as if its report asked for `variant` between its two leading
    candidates, their predictions on it run as a report runs them: the variant need not part them
    (a difference of SEPARATES, the least that does, is set), only be written. The report's own
    separation is put back."""
    fits = [j.fit for j in d.candidates[:2]]
    _, runs = _differences(d.problem, fits[0], fits[1], variant)
    experiment = d.problem.experiment
    declared = experiment.inflation_gauge_pressure_Pa if experiment.gas == GasMode.sealed else None
    kept = d.separation
    d.separation = Separation(tuple(f.name for f in fits), variant, declared, {"force_N": SEPARATES}, {}, {}, runs)
    try:
        return write_next_test(d, path)
    finally:
        d.separation = kept


def test_a_slower_variant_scales_the_motions_times(tie, tmp_path):
    # On the tie the slower test does not part the two (0.5x the noise); written all the same.
    path, d = tie
    written = written_as_if_asked(d, Variant("slower", time_scale=10.0), tmp_path / "slow" / "next.toml")
    experiment, first = load_experiment(written[0]), load_experiment(path)
    np.testing.assert_allclose(experiment.time_s, 10.0 * first.time_s, rtol=1e-9)
    assert experiment.initial_length_m == first.initial_length_m  # the same inflation: the same start
    assert experiment.inflation_gauge_pressure_Pa == first.inflation_gauge_pressure_Pa


def test_a_zero_run_writes_the_predictions_only(tie, tmp_path):
    _, d = tie
    written = written_as_if_asked(d, Variant("zero_run", zero_reading=True), tmp_path / "next.toml")
    assert written == [tmp_path / "next.predictions.csv"]
    assert not (tmp_path / "next.toml").exists()
    header, values = read_predictions(written[0])
    assert values.shape[0] == 2 and header[2].startswith("force_N [")


def test_no_test_asked_for_writes_nothing_and_says_why(thesis_dir, tmp_path, run_pamkit):
    example = thesis_dir.parent / "example" / "experiment.toml"  # heat transfer, named with no rival near
    done = run_pamkit("diagnose", example, "--quiet", "--next-test", tmp_path / "next.toml")
    assert done.returncode == 0, done.stderr
    assert "--next-test: nothing written: the report asks for no further test" in done.stderr
    assert not list(tmp_path.iterdir())
    assert asked_for(None) is not None


def test_a_campaign_or_a_table_names_no_next_test(thesis_dir, tmp_path):
    table = diagnose(thesis_dir.parent / "isotonic" / "isotonic.toml", threads=2)
    with pytest.raises(ValueError, match="one time series' report names the test to run next"):
        write_next_test(table, tmp_path / "next.toml")


def test_a_report_writes_its_next_test(tie, tmp_path):
    path, d = tie
    report = Report(to_json(d), verdict(d), d)
    written = report.write_next_test(tmp_path / "next.toml")
    assert written == [tmp_path / "next.toml", tmp_path / "next.csv", tmp_path / "next.predictions.csv"]
    with pytest.raises(ValueError, match="read from JSON"):
        Report(to_json(d)).write_next_test(tmp_path / "again.toml")


def test_a_supplied_tests_next_test_scales_the_pressure_it_supplies(thesis_dir, tmp_path):
    path = thesis_dir.parent / "supplied" / "isometric_sweep.toml"
    d = diagnose(path, threads=2)  # its report asks for no test: written as if it asked for this one
    higher = Variant("pressure_higher", pressure_share=0.5)
    written = load_experiment(written_as_if_asked(d, higher, tmp_path / "next.toml")[0])
    first = load_experiment(path)
    assert written.gas == first.gas and written.initial_length_m == first.initial_length_m
    np.testing.assert_allclose(
        written.columns["gauge_pressure_Pa"], 1.5 * first.columns["gauge_pressure_Pa"], rtol=1e-9
    )
    np.testing.assert_allclose(written.time_s, first.time_s, rtol=1e-9)
