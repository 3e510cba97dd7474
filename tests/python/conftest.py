import os
import subprocess
import sys
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("PAMKIT_SOURCE_DIR", Path(__file__).resolve().parents[2]))


@pytest.fixture
def thesis_dir() -> Path:
    return SOURCE_DIR / "data" / "experiments" / "thesis"


@pytest.fixture
def write_experiment(tmp_path):
    """Writes an experiment TOML (PAM 2 of the thesis, 207 kPa, table C.2) and its CSV into
    tmp_path; `toml_extra` lines are appended to [test], `csv_text` replaces the data."""

    def write(
        csv_text="time_s,elongation_m\n0,0\n1,0.0025\n2,0.005\n", toml_test_extra="", sections="", muscle_extra=""
    ):
        (tmp_path / "run.csv").write_text(csv_text)
        path = tmp_path / "run.toml"
        path.write_text(
            "[muscle]\nlength_m = 0.225\ndiameter_m = 0.020\nbladder_diameter_m = 0.01545\n"
            "bladder_thickness_m = 0.000254\nfiber_count = 216\nfiber_revolutions = 2\n"
            "fiber_thickness_m = 0.000254\nend_diameter_m = 0.013\ncone_generator_m = 0.0095\n"
            f"{muscle_extra}\n"
            "[test]\ninflation_pressure_kPa = 236.63\nambient_temperature_C = 22.85\ninitial_length_m = 0.167\n"
            f'data = "run.csv"\n{toml_test_extra}\n{sections}'
        )
        return path

    return write


@pytest.fixture
def run_pamkit():
    """`python -m pamkit ARGUMENTS...` as a user runs it: a real process with this test's
    environment, its output captured as text; returns the CompletedProcess. `timeout` [s] bounds
    a command that hangs."""

    def run(*arguments, timeout=300):
        return subprocess.run(
            [sys.executable, "-m", "pamkit", *map(str, arguments)],
            capture_output=True,
            text=True,
            env=os.environ.copy(),
            timeout=timeout,
        )

    return run
