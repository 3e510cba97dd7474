"""`pamkit diagnose --batch DIR`: every experiment of a folder diagnosed on a 2-worker local Dask
cluster, one row each, the same row as diagnosing the file in this process, and a file that
cannot be diagnosed kept as a row with its message."""

import shutil

import pytest

from pamkit import cli
from pamkit.cluster import read_rows
from pamkit.diagnosis.batch import batch_files, diagnose_file
from pamkit.synth.dataset import synthesize


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """Two synthetic tests (a leak strong enough to name, tau = 300 s; nothing hidden) and a file
    with no [test], side by side in one folder."""
    made = tmp_path_factory.mktemp("made")
    folder = tmp_path_factory.mktemp("batch")
    for name, effect, seed in (("leak", "leak:time_constant_s=300", 5), ("plain", "none", 3)):
        files = synthesize(effect, seed, made / name)
        shutil.copy(files.data, folder / f"{name}.csv")
        (folder / f"{name}.toml").write_text(
            files.experiment.read_text().replace(f'"{files.data.name}"', f'"{name}.csv"')
        )
    (folder / "broken.toml").write_text("[muscle]\nlength_m = 0.225\n")
    return folder


def test_each_test_is_one_row_and_a_broken_file_keeps_its_message(folder, tmp_path, capsys):
    output = tmp_path / "batch.parquet"
    arguments = ["diagnose", "--batch", str(folder), "-o", str(output), "--workers", "2", "--quiet"]
    assert cli.main(arguments) == 0
    assert capsys.readouterr().out == f"wrote {output} (3 tests, 1 failed)\n"
    broken, leak, plain = read_rows(output)  # in file-name order
    assert broken["error"].endswith("broken.toml: missing section [test]") and broken["cause"] is None
    assert leak["cause"] == "leak" and leak["gain_gauge_pressure_Pa"] > 0.5 and leak["error"] is None
    assert plain["cause"] == "none" and plain["gain_force_N"] == 0.0
    for row in (leak, plain):
        assert row["heldout_rmse_force_N"] > 0 and row["warnings"] >= 0
    # Each diagnosis seeds its bootstrap from its data: the worker's row is this process's row.
    here = diagnose_file(folder / "leak.toml")
    assert {k: v for k, v in leak.items() if k != "seconds"} == {k: v for k, v in here.items() if k != "seconds"}


def test_batch_and_positional_experiments_do_not_mix(folder, tmp_path, capsys):
    assert cli.main(["diagnose", str(folder / "leak.toml"), "--batch", str(folder), "-o", "x.csv"]) == 2
    assert "name no experiment besides it" in capsys.readouterr().err
    assert cli.main(["diagnose", "--batch", str(folder)]) == 2
    assert "--batch needs -o" in capsys.readouterr().err
    assert cli.main(["diagnose", str(folder / "leak.toml"), "--workers", "2"]) == 2
    assert "--workers belongs to --batch" in capsys.readouterr().err


def test_a_folder_without_experiments_is_named(tmp_path):
    with pytest.raises(ValueError, match=f"--batch {tmp_path}: no experiment TOML file in it"):
        batch_files(tmp_path)
