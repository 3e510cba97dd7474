"""The command line as a user runs it: a real process, real files."""

import csv
from pathlib import Path

import numpy as np
import pytest

import pamkit


def read_csv(path):
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    return rows[0], np.array(rows[1:], dtype=float)


def test_simulate_thesis_test_writes_csv_and_plot(thesis_dir, tmp_path, run_pamkit):
    output = tmp_path / "out.csv"
    plot = tmp_path / "out.png"
    done = run_pamkit("simulate", thesis_dir / "pam2_207kPa_90pct.toml", "-o", output, "--plot", plot)
    assert done.returncode == 0, done.stderr
    header, table = read_csv(output)
    assert header[:5] == ["time_s", "elongation_m", "force_N", "pressure_kPa", "temperature_C"]
    # The input's time and elongation come back unchanged (table C.2: 52.3 mm, 10 cycles at 2.5 mm/s).
    assert table[:, 1].max() == pytest.approx(0.0523)
    assert table[-1, 0] == pytest.approx(20 * 0.0523 / 2.5e-3)
    # Starts at the transducer's inflation pressure (table C.2) and the ambient 296 K (table C.4).
    assert table[0, 3] == pytest.approx(236.63)
    assert table[0, 4] == pytest.approx(22.85)
    # A sealed gas is compressed by stretching (the volume falls): pressure peaks with elongation.
    peak = np.argmax(table[:, 1])
    assert table[peak, 3] > table[0, 3] + 50
    assert plot.stat().st_size > 10_000 and plot.read_bytes()[:4] == b"\x89PNG"


def test_simulate_supplied_uses_measured_pressure(write_experiment, tmp_path, run_pamkit):
    path = write_experiment(
        csv_text="time_s,elongation_m,pressure_kPa\n0,0,200\n1,0,300\n2,0,400\n", toml_test_extra='gas = "supplied"'
    )
    output = tmp_path / "supplied.csv"
    done = run_pamkit("simulate", path, "-o", output)
    assert done.returncode == 0, done.stderr
    _, table = read_csv(output)
    np.testing.assert_allclose(table[:, 3], [200, 300, 400])
    # Isometric and supplied: more pressure, more force at the same length.
    assert np.all(np.diff(table[:, 2]) > 0)


def test_simulate_reports_bad_input_without_traceback(write_experiment, tmp_path, run_pamkit):
    path = write_experiment(csv_text="time_s,elongation_m\n0,0\n1,oops\n")
    done = run_pamkit("simulate", path, "-o", tmp_path / "x.csv")
    assert done.returncode == 2
    assert "run.csv:3: column 2 (elongation_m) = 'oops' is not a number" in done.stderr
    assert "Traceback" not in done.stderr


def test_simulate_names_the_row_that_leaves_the_braid_range(write_experiment, tmp_path, run_pamkit):
    path = write_experiment(csv_text="time_s,elongation_m\n0,0\n1,0.01\n2,0.5\n")
    done = run_pamkit("simulate", path, "-o", tmp_path / "x.csv")
    assert done.returncode == 2
    assert "run.csv" in done.stderr and "trajectory sample 2" in done.stderr


def test_help_lists_the_exit_statuses(capsys):
    from pamkit.cli import main

    with pytest.raises(SystemExit):
        main(["--help"])
    assert "2 bad input" in capsys.readouterr().out


def test_an_output_that_cannot_be_written_is_one_line_with_status_2(tmp_path, capsys):
    from pamkit.cli import main

    blocker = tmp_path / "a_file"
    blocker.write_text("")
    experiment = Path(__file__).resolve().parents[2] / "data" / "experiments" / "festo" / "DMSP-10-250.toml"
    assert main(["simulate", str(experiment), "-o", str(blocker / "out.csv")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("pamkit simulate: error:") and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize(
    "raised, status, says",
    [
        (pamkit.SolverError("CV_CONV_FAILURE at t = 1.2 s"), 3, "the model cannot follow this input"),
        (ZeroDivisionError("division by zero"), 1, "this is a bug in pamkit; please report it"),
    ],
)
def test_solver_failures_and_bugs_have_their_own_status(monkeypatch, capsys, raised, status, says):
    import pamkit.commands.simulate as simulate_command
    from pamkit.cli import main

    def fail(arguments):
        raise raised

    monkeypatch.setattr(simulate_command, "run", fail)
    assert main(["simulate", "x.toml", "-o", "y.csv"]) == status
    err = capsys.readouterr().err
    assert says in err
    # A solver's failure is the input's: one line. A bug keeps its traceback for the report.
    assert (len(err.strip().splitlines()) == 1) if status == 3 else err.startswith("Traceback")
