"""Sweeps on Dask (pamkit sweep): the rows a 2-worker local cluster gives are the rows of a plain
loop, a failed run keeps its message, a Latin hypercube is one with its seed, and a sweep cut
short resumes from its journal."""

import json
import math
import sys

import numpy as np
import pyarrow.parquet as pq
import pytest

from pamkit import cli
from pamkit.cluster import ScaleUnavailable, client, read_rows, require
from pamkit.io.guards import ExperimentError
from pamkit.sweep import METRICS, batch_rows, load_spec, run_chunk, run_in_process, run_one, sweep

# One cycle of the thesis's PAM 2 test at 207 kPa (table C.2): a short run, about 300 samples.
BASE = '[sweep]\nexperiment = "{base}"\ncycles = 1\n'
# 2 pressures x 3 braid angles around PAM 2's own 31.2 deg (2 revolutions over 225 mm); below
# about 26 deg the braid cannot shorten to the test's 0.167 m.
GRID = """
[parameters]
inflation_pressure_kPa = {{ values = [150, 250] }}
braid_angle_deg = {{ linspace = [28, 34, 3] }}
"""


@pytest.fixture(scope="module")
def cluster():
    with client(workers=2) as connected:
        yield connected


@pytest.fixture
def write_spec(tmp_path, thesis_dir):
    def write(text, name="spec.toml"):
        path = tmp_path / name
        path.write_text(BASE.format(base=(thesis_dir / "pam2_207kPa_80pct.toml").as_posix()) + text)
        return path

    return write


def test_a_two_worker_cluster_gives_the_rows_of_a_plain_loop(cluster, write_spec, tmp_path):
    spec = load_spec(write_spec(GRID.format()))
    assert len(spec.runs) == 6
    output = tmp_path / "results.parquet"
    rows = sweep(spec, output, cluster)
    assert rows == run_in_process(spec)  # the same numbers, bit for bit: Dask changes nothing
    assert read_rows(output) == rows
    assert str(pq.read_schema(output).field("error").type) == "string"  # text even when no run failed
    assert not (tmp_path / "results.parquet.partial.jsonl").exists()
    assert all(row["error"] is None for row in rows)
    # Physics, not bookkeeping: at each braid angle a higher pressure pulls harder and stores
    # more energy over the stretch (the force grows with the pressure at every length).
    for angle in {row["braid_angle_deg"] for row in rows}:
        low, high = sorted(
            (r for r in rows if r["braid_angle_deg"] == angle), key=lambda r: r["inflation_pressure_kPa"]
        )
        assert high["peak_force_N"] > low["peak_force_N"] > 0
        assert high["stored_energy_J"] > low["stored_energy_J"] > 0
        assert low["pressure_range_Pa"] > 0  # a sealed test: the volume changes, so does the pressure
        assert low["temperature_swing_K"] == 0  # the files' gas is isothermal (polytropic, n = 1)


def test_a_run_the_model_cannot_follow_keeps_its_message_and_the_others_run(cluster, write_spec, tmp_path):
    # PAM 2's fibers are sqrt(0.225^2 + (2 pi 0.02)^2) = 0.258 m long: a muscle mounted at 0.30 m
    # is longer than its braid can stretch.
    spec = load_spec(write_spec("[parameters]\ninitial_length_m = { values = [0.167, 0.30] }\n"))
    output = tmp_path / "results.csv"
    rows = sweep(spec, output, cluster)
    assert rows[0]["error"] is None and rows[0]["peak_force_N"] > 0
    assert "braid" in rows[1]["error"]
    assert all(math.isnan(rows[1][metric]) for metric in METRICS)
    assert [row["error"] for row in read_rows(output)] == ["", rows[1]["error"]]


def test_a_combination_the_build_rejects_is_a_failed_run(write_spec):
    # The bladder (15.45 mm) inside a 12 mm braid: MuscleBuild.validate refuses it.
    spec = load_spec(write_spec("[parameters]\ndiameter_m = { values = [0.02, 0.012] }\n"))
    assert run_one(spec, 0)["error"] is None
    assert "bladder" in run_one(spec, 1)["error"]


def test_a_batch_of_runs_gives_the_rows_of_one_run_at_a_time_bit_for_bit(write_spec):
    # A sealed test's runs go through one C++ batch (Simulator.run_batch over ParameterSets, the
    # spec's kPa and degrees Celsius converted once for all runs); run_one still simulates one
    # experiment at a time through simulate_experiment. The rows must not differ, not even in the
    # last bit or in an error's wording: a bladder the braid cannot hold, a muscle mounted past
    # the braid's reach, a room of another temperature, a thousandfold friction sharpness.
    lhs = """[parameters]
inflation_pressure_kPa = { range = [100, 300] }
braid_angle_deg = { range = [24, 35] }
ambient_temperature_C = { range = [0, 40] }
friction.sharpness_s_per_m = { range = [0.5, 1000] }
"""
    path = write_spec(lhs)
    path.write_text(
        path.read_text().replace("[sweep]\n", '[sweep]\ndesign = "latin_hypercube"\nsamples = 24\nseed = 3\n')
    )
    grid = load_spec(
        write_spec(
            "[parameters]\ninitial_length_m = { values = [0.167, 0.30] }\ndiameter_m = { values = [0.02, 0.012] }\n",
            "grid.toml",
        )
    )
    for spec in (load_spec(path), grid):
        runs = list(range(len(spec.runs)))
        batched = batch_rows(spec, runs, threads=2)
        assert json.dumps(batched) == json.dumps([run_one(spec, run) for run in runs])  # NaN-safe
    assert {row["error"] is None for row in batched} == {True, False}  # the grid has both


def test_a_chunk_is_one_batch_where_the_test_is_sealed(write_spec, tmp_path, monkeypatch):
    import pamkit.sweep

    spec = load_spec(write_spec(GRID.format()))
    calls = []
    real = pamkit.sweep.batch_rows
    monkeypatch.setattr(pamkit.sweep, "batch_rows", lambda *args, **kwargs: calls.append(args) or real(*args, **kwargs))
    rows = run_chunk(spec, [0, 3, 5])
    assert len(calls) == 1 and [row["run"] for row in rows] == [0, 3, 5]
    exo = tmp_path / "exo.toml"
    exo.write_text('[sweep]\ndevice = "exoskeleton"\n[parameters]\nexo.play_deg = { values = [0, 4] }\n')
    assert len(run_chunk(load_spec(exo), [0, 1])) == 2 and len(calls) == 1  # run by run


def test_a_latin_hypercube_is_reproduced_by_its_seed_and_stratifies_each_parameter(write_spec):
    lhs = """[parameters]
inflation_pressure_kPa = { range = [100, 300] }
bladder.shear_modulus_Pa = { range = [0.5e6, 2e6] }
"""
    design = '[sweep]\ndesign = "latin_hypercube"\nsamples = 10\nseed = {seed}\n'

    def runs(seed, name):
        path = write_spec(lhs, name)
        path.write_text(path.read_text().replace("[sweep]\n", design.format(seed=seed)))
        return np.array(load_spec(path).runs)

    first, again, other = runs(7, "a.toml"), runs(7, "b.toml"), runs(8, "c.toml")
    np.testing.assert_array_equal(first, again)
    assert not np.array_equal(first, other)
    # A Latin hypercube puts exactly one of its 10 samples in each tenth of every range.
    for column, (low, high) in zip(first.T, [(100, 300), (0.5e6, 2e6)]):
        strata = np.floor((column - low) / (high - low) * 10).astype(int)
        assert sorted(strata) == list(range(10))


def test_a_sweep_cut_short_resumes_from_its_journal(cluster, write_spec, tmp_path):
    spec = load_spec(write_spec(GRID.format()))
    output = tmp_path / "results.parquet"
    journal = tmp_path / "results.parquet.partial.jsonl"
    done = run_one(spec, 0)
    done["peak_force_N"] = -1.0  # a mark: a resumed sweep keeps this row instead of running it again
    cut = json.dumps(run_one(spec, 1))[:25]  # the line a crash cut short
    journal.write_text(json.dumps({"work": spec.work_key()}) + "\n" + json.dumps(done) + "\n" + cut)
    rows = sweep(spec, output, cluster)
    assert rows[0]["peak_force_N"] == -1.0
    assert rows[1:] == run_in_process(spec)[1:]
    assert not journal.exists()


def test_a_journal_of_other_work_is_not_resumed(cluster, write_spec, tmp_path):
    spec = load_spec(write_spec(GRID.format()))
    output = tmp_path / "results.parquet"
    (tmp_path / "results.parquet.partial.jsonl").write_text('{"work": "another"}\n')
    with pytest.raises(ValueError, match="partial results of other work"):
        sweep(spec, output, cluster)


@pytest.mark.parametrize(
    ("parameters", "message"),
    [
        ("stiffness = { values = [1] }", r"spec.toml: \[parameters\] stiffness: not a parameter a sweep can set"),
        ("length_m = { values = [9] }", r"\[parameters\] length_m: 9 m leaves the allowed \[0.01, 5\]"),
        ("length_m = { range = [0.1, 0.2] }", r"a grid takes \{ values = \[...\] \} or \{ linspace"),
        ("length_m = { linspace = [0.1, 0.2, 0] }", "count 0 must be at least 1"),
        ("", r"\[parameters\] is empty"),
    ],
)
def test_a_bad_spec_is_named_by_file_and_key(write_spec, parameters, message):
    with pytest.raises(ExperimentError, match=message):
        load_spec(write_spec(f"[parameters]\n{parameters}\n"))


def test_the_command_line_writes_the_table_on_a_running_cluster(cluster, write_spec, tmp_path, capsys):
    output = tmp_path / "results.csv"
    spec = write_spec("[parameters]\ngas.polytropic_index = { values = [1.0, 1.4] }\n")
    address = cluster.scheduler.address  # as a lab passes its cluster's scheduler
    assert cli.main(["sweep", str(spec), "-o", str(output), "--scheduler", address, "--quiet"]) == 0
    assert capsys.readouterr().out == f"wrote {output} (2 runs, 0 failed)\n"
    isothermal, adiabatic = read_rows(output)
    assert float(isothermal["temperature_swing_K"]) == 0  # n = 1: the gas keeps its temperature
    assert float(adiabatic["temperature_swing_K"]) > 1  # n = 1.4: a few percent of volume change, degrees


def test_without_dask_the_command_says_what_to_install(write_spec, tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # what an environment without Dask imports
    with pytest.raises(ScaleUnavailable, match=r"pip install 'pamkit\[scale\]'"):
        require("distributed")
    spec = write_spec(GRID.format())
    assert cli.main(["sweep", str(spec), "-o", str(tmp_path / "r.parquet")]) == 2
    assert capsys.readouterr().err.strip().endswith("distributed is not installed: pip install 'pamkit[scale]'")


@pytest.mark.parametrize(("example", "runs"), [("pam2_pressure_angle.toml", 12), ("exo_play.toml", 15)])
def test_the_bundled_examples_run_without_a_failure(thesis_dir, example, runs):
    rows = run_in_process(load_spec(thesis_dir.parents[1] / "sweeps" / example))
    assert len(rows) == runs and [row["error"] for row in rows] == [None] * runs


def test_a_spec_without_an_experiment_sweeps_the_thesis_test(thesis_dir):
    spec = load_spec(thesis_dir.parents[1] / "sweeps" / "pam2_pressure_angle.toml")
    assert spec.experiment == thesis_dir / "pam2_207kPa_80pct.toml"


def test_an_exoskeleton_sweep_gives_the_clutch_timing_on_dask(cluster, tmp_path):
    spec_path = tmp_path / "exo.toml"
    spec_path.write_text(
        '[sweep]\ndevice = "exoskeleton"\n[parameters]\nexo.play_deg = { values = [0, 8] }\n'
        "exo.block_angle_deg = { values = [100, 500] }\n"
    )
    with pytest.raises(ExperimentError, match=r"exo.block_angle_deg: 500 deg leaves the allowed \[1, 179\]"):
        load_spec(spec_path)
    spec_path.write_text(spec_path.read_text().replace("[100, 500]", "[100]"))
    spec = load_spec(spec_path)
    rows = sweep(spec, tmp_path / "exo.parquet", cluster)
    assert json.dumps(rows) == json.dumps(run_in_process(spec))  # NaN-safe: a clutch that never releases
    fitted, with_play = rows
    # The clutch's screws fitted to the normal gait release it at 64.8 % of the stride, after
    # toe-off (59.4 %); with 8 deg of play between leg and device it never releases (chapter 5,
    # README "Exoskeleton").
    assert fitted["release_pct"] == pytest.approx(64.8, abs=0.05) and fitted["error"] is None
    assert (
        math.isnan(with_play["release_pct"])
        and with_play["engaged_share_of_stride"] > fitted["engaged_share_of_stride"]
    )


def test_a_swept_experiment_keeps_its_muscles_construction():
    # The construction is an enum beside the build's numbers: a swept copy of an embedded Festo
    # muscle must stay embedded (its braid cannot push), whatever field the sweep moves.
    from conftest import SOURCE_DIR

    from pamkit import Construction
    from pamkit.io.experiment import load_experiment
    from pamkit.sweep import with_parameters

    base = load_experiment(SOURCE_DIR / "data" / "experiments" / "festo" / "DMSP-20-300.toml")
    assert base.build.construction == Construction.embedded
    swept = with_parameters(base, {"length_m": 0.29})
    assert swept.build.length_m == 0.29 and swept.build.construction == Construction.embedded
    assert base.build.length_m == 0.3  # the base left as it was
