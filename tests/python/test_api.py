"""The scientist's API (issue #12): pamkit.load_experiment, pamkit.simulate (a DataFrame with units
in its column names and the solver's statistics) and pamkit.diagnose (a report), from `import
pamkit` alone, beside the modules they were before."""

import inspect
import json
import pydoc

import numpy as np
import pandas as pd
import pytest

import pamkit
from pamkit.effects import parse_effects
from pamkit.io.guards import ExperimentError
from pamkit.simulate import simulate_experiment

SERIES_COLUMNS = ["time_s", "elongation_m", "force_N", "gauge_pressure_Pa", "temperature_K"]


@pytest.fixture
def machines_dir(thesis_dir):
    return thesis_dir.parent / "machines"


def test_simulate_returns_the_prediction_as_a_frame(machines_dir):
    toml = machines_dir / "zwick_testxpert.toml"
    frame = pamkit.simulate(toml)
    assert isinstance(frame, pd.DataFrame)
    assert list(frame.columns) == SERIES_COLUMNS
    # The same numbers as the numpy implementation the command line uses.
    columns = simulate_experiment(pamkit.load_experiment(toml))
    for name in SERIES_COLUMNS:
        np.testing.assert_array_equal(frame[name].to_numpy(), columns[name])
    assert frame.attrs["units"] == {
        "time_s": "s",
        "elongation_m": "m",
        "force_N": "N",
        "gauge_pressure_Pa": "Pa",
        "temperature_K": "K",
    }
    assert frame.attrs["experiment"] == str(toml) and frame.attrs["data"].endswith("zwick_testxpert.csv")
    assert frame.attrs["kind"] == "series" and frame.attrs["gas"] == "sealed" and frame.attrs["effects"] == []


def test_the_solver_statistics_come_with_a_sealed_run(machines_dir):
    statistics = pamkit.simulate(machines_dir / "instron_bluehill.toml").attrs["solver_statistics"]
    # CVODES invariants: every step takes at least one right-hand-side evaluation, every
    # Newton iteration one, and the one corner of the triangle (t = 4 s) restarts the solver.
    assert statistics["steps"] > 0
    assert statistics["rhs_evaluations"] >= statistics["steps"]
    assert statistics["nonlinear_iterations"] >= statistics["steps"]
    assert statistics["restarts"] >= 1
    assert statistics["method"] == "bdf"  # SimulatorConfig's default
    json.dumps(statistics)  # plain ints: attrs survive pandas' copies and serialise


def test_a_supplied_test_integrates_no_ode(write_experiment):
    path = write_experiment(
        csv_text="time_s,elongation_m,pressure_kPa\n0,0,100\n1,0.001,110\n2,0.002,120\n",
        toml_test_extra='gas = "supplied"',
    )
    frame = pamkit.simulate(pamkit.load_experiment(path))
    assert frame.attrs["solver_statistics"] is None
    np.testing.assert_array_equal(frame["gauge_pressure_Pa"], [100e3, 110e3, 120e3])  # the measured pressure drove it


def test_effects_are_objects_or_specs(machines_dir):
    toml = machines_dir / "instron_bluehill.toml"
    spec = "heat_transfer:time_constant_s=2"
    by_spec = pamkit.simulate(toml, effects=[spec])
    effect = parse_effects([spec])[0]
    by_object = pamkit.simulate(toml, effects=[effect])
    pd.testing.assert_frame_equal(by_spec, by_object)
    assert by_spec.attrs["effects"] == [repr(effect)]
    # The effect changes the prediction: heat flows through the wall over the 8 s test.
    assert not np.array_equal(by_spec["temperature_K"], pamkit.simulate(toml)["temperature_K"])
    with pytest.raises(ExperimentError, match=r"instron_bluehill.toml: .*no_such_effect"):
        pamkit.simulate(toml, effects=["no_such_effect"])


def test_a_static_table_comes_back_with_its_own_columns(thesis_dir):
    festo = thesis_dir.parent / "festo" / "DMSP-10-250.toml"
    frame = pamkit.simulate(festo)
    experiment = pamkit.load_experiment(festo)
    assert list(frame.columns) == ["length_m", "gauge_pressure_Pa", "force_N"]
    assert len(frame) == len(experiment.columns["force_N"]) and frame.attrs["solver_statistics"] is None


def test_diagnose_returns_a_report(tmp_path, thesis_dir):
    report = pamkit.diagnose(thesis_dir.parent / "festo" / "DMSP-10-250.toml", threads=2)
    assert isinstance(report, pamkit.diagnose.Report)
    # The report's methods are the module functions' answers on the same diagnosis.
    assert report.verdict() == pamkit.diagnose.verdict(report.diagnosis)
    text = report.to_json(tmp_path / "report.json")
    assert json.loads(text) == json.loads((tmp_path / "report.json").read_text())
    assert json.loads(text)["cause"] == report.to_dict()["cause"] == report.diagnosis.cause
    assert report.plot(tmp_path / "report.png").read_bytes()[:4] == b"\x89PNG"
    assert report.verdict() in repr(report)


def test_the_modules_stay_importable_beside_the_calls():
    import pamkit.diagnose.engine as engine  # `import a.b.c as d` looks b up on a: must be the module
    from pamkit.diagnose import diagnose
    from pamkit.simulate import simulate_experiment as again

    assert again is simulate_experiment and engine.diagnose is diagnose
    assert callable(pamkit.simulate) and callable(pamkit.diagnose)
    assert "experiment_or_path" in inspect.signature(pamkit.simulate).parameters
    assert "path_or_experiments" in inspect.signature(pamkit.diagnose).parameters
    assert {"load_experiment", "simulate", "diagnose"} <= set(pamkit.__all__) and "simulate" in dir(pamkit)


@pytest.mark.parametrize(
    "name, says",
    [
        ("load_experiment", ["time_s [s]", "elongation_m [m]", "force_N [N]", "N (rows"]),
        ("simulate", ["time_s [s]", "force_N [N]", "gauge_pressure_Pa [Pa]", "N rows", "solver_statistics"]),
        ("diagnose", ["verdict()", "to_json", "plot(path)"]),
    ],
)
def test_help_says_units_and_shapes(name, says):
    text = pydoc.render_doc(getattr(pamkit, name), renderer=pydoc.plaintext)
    for phrase in says:
        assert phrase in text, f"help(pamkit.{name}) does not say {phrase!r}"


def test_the_notebook_script_runs_from_import_pamkit_alone(tmp_path, machines_dir):
    # The README-style first hour, verbatim: load, simulate to a DataFrame, diagnose, plot.
    script = f"""
import pamkit
experiment = pamkit.load_experiment({str(machines_dir / "zwick_testxpert.toml")!r})
df = pamkit.simulate(experiment, effects=["heat_transfer:time_constant_s=2"])
ax = df.plot(x="time_s", y="force_N", label="predicted")
ax.plot(experiment.time_s, experiment.columns["force_N"], ".", label="ZwickRoell export")
ax.figure.savefig({str(tmp_path / "force.png")!r})
report = pamkit.diagnose({str(machines_dir.parent / "festo" / "DMSP-10-250.toml")!r}, threads=2)
print(report.verdict())
report.plot({str(tmp_path / "report.png")!r})
"""
    import matplotlib
    import matplotlib.pyplot

    matplotlib.use("Agg")
    exec(compile(script, "notebook", "exec"), {})
    matplotlib.pyplot.close("all")
    assert (tmp_path / "force.png").read_bytes()[:4] == b"\x89PNG"
    assert (tmp_path / "report.png").read_bytes()[:4] == b"\x89PNG"
