"""A sealed test simulated in blocks: `pamkit simulate` writes a long test's prediction
as it is integrated, and what it writes is what the whole prediction gives, byte for byte."""

import numpy as np
import pytest

from pamkit._core import EffectCatalog
from pamkit.cli import main
from pamkit.io.columns import SERIES_COLUMNS
from pamkit.io.experiment import load_experiment
from pamkit.io.guards import ExperimentError
from pamkit.io.writers import write_series
from pamkit.simulation import simulate_experiment, simulate_streamed, why_not_streamed

EFFECTS = EffectCatalog.builtin()


@pytest.fixture
def thesis_test(thesis_dir):
    """A thesis bench test: PAM 1 sealed at 35 kPa, 2 901 samples."""
    return thesis_dir / "pam1_035kPa_95pct.toml"


@pytest.mark.parametrize("specs", [[], ["heat_transfer:time_constant_s=2", "fixture_slack:slack_m=0.001"]])
def test_blocks_joined_equal_the_whole_prediction_bit_for_bit(thesis_test, specs):
    experiment = load_experiment(thesis_test)
    experiment.ranges["force_N"] = (-1e3, 40.0)  # a load cell that clips: read block by block too
    effects = [EFFECTS.parse(spec) for spec in specs]
    whole = simulate_experiment(experiment, effects=effects)
    blocks = []
    statistics = simulate_streamed(experiment, blocks.append, effects=effects, block_rows=97)
    assert [len(block["time_s"]) for block in blocks] == [97] * 29 + [2901 - 29 * 97]
    assert all(list(block) == list(SERIES_COLUMNS) for block in blocks)
    for name in SERIES_COLUMNS:
        assert np.array_equal(np.concatenate([block[name] for block in blocks]), whole[name]), name
    assert whole["force_N"].max() == 40.0  # the clip acted
    assert statistics.steps > 0 and statistics.output_evaluations == 2901


def test_simulate_writes_the_same_bytes_streamed(thesis_test, tmp_path, capsys):
    streamed = tmp_path / "streamed.csv"
    assert main(["simulate", str(thesis_test), "-o", str(streamed)]) == 0
    assert f"wrote {streamed} (2901 samples: time_s, elongation_m" in capsys.readouterr().out
    whole = tmp_path / "whole.csv"
    write_series(whole, simulate_experiment(load_experiment(thesis_test)))
    assert streamed.read_bytes() == whole.read_bytes()


def test_effects_on_the_measured_series_are_simulated_whole(thesis_test, tmp_path):
    # A lag filter reads the samples before each block: not streamed, the CLI simulates whole.
    experiment = load_experiment(thesis_test)
    lag = [EFFECTS.parse("sensor_lag:time_constant_s=0.5")]
    assert why_not_streamed(experiment, lag) == "sensor_lag act(s) on the whole measured series"
    with pytest.raises(ExperimentError, match=r"pam1_035kPa_95pct.toml: cannot stream the simulation: sensor_lag"):
        simulate_streamed(experiment, lambda block: None, effects=lag)
    output = tmp_path / "lagged.csv"
    assert main(["simulate", str(thesis_test), "--effect", "sensor_lag:time_constant_s=0.5", "-o", str(output)]) == 0
    whole = tmp_path / "whole.csv"
    write_series(whole, simulate_experiment(experiment, effects=lag))
    assert output.read_bytes() == whole.read_bytes()


def test_a_simulation_that_fails_leaves_no_csv(write_experiment, tmp_path, capsys):
    # 0.5 m of stretch takes PAM 2 beyond its braid's range: refused before the first sample.
    path = write_experiment("time_s,elongation_m\n0,0\n1,0.25\n2,0.5\n")
    output = tmp_path / "out.csv"
    assert main(["simulate", str(path), "-o", str(output)]) == 2
    assert "outside the braid's range" in capsys.readouterr().err
    assert not output.exists()
