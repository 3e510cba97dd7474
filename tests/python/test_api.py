"""The scientist's API, from `import pamkit` alone: pamkit.load_experiment, pamkit.simulate (a
DataFrame with units in its column names and the solver's statistics), pamkit.diagnose (a Report:
the verdict, the candidates and causes as DataFrames, JSON, a figure, a notebook display), and an
experiment to and from a DataFrame."""

import html
import inspect
import json
import pydoc
import re
import subprocess
import sys
import types

import numpy as np
import pandas as pd
import pytest
from conftest import SOURCE_DIR

import pamkit
from pamkit.effects import parse_effects
from pamkit.io.guards import ExperimentError
from pamkit.simulation import simulate_experiment
from pamkit.units import KELVIN_AT_ZERO_CELSIUS, PASCAL_PER_KILOPASCAL

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
    assert isinstance(report, pamkit.Report)
    # The report's answers are the diagnosis package's functions' on the same diagnosis.
    assert report.verdict() == pamkit.diagnosis.verdict(report.diagnosis)
    assert report.to_dict() == pamkit.diagnosis.to_json(report.diagnosis)
    text = report.to_json(tmp_path / "report.json")
    assert json.loads(text) == json.loads((tmp_path / "report.json").read_text())
    assert json.loads(text)["cause"] == report.cause == report.diagnosis.cause
    assert report.kind == "isometric_map" and report.channels == ["force_N"]
    assert report.plot(tmp_path / "report.png").read_bytes()[:4] == b"\x89PNG"
    assert report.verdict() in repr(report)
    # The same figure, open to look at; plot closed its own.
    import matplotlib.pyplot as plt

    figure = report.figure()
    assert plt.fignum_exists(figure.number) and figure.get_axes()
    plt.close(figure)


def test_drawing_keeps_a_sessions_backend_and_needs_no_display_where_none_is_chosen():
    # A notebook or a script that imported pyplot keeps its backend; a process that has not (the
    # command line) draws with Agg, which needs no display.
    draw = "from pamkit.plots import pyplot; pyplot(); import matplotlib; print(matplotlib.get_backend())"
    chosen = "import matplotlib; matplotlib.use('pdf'); import matplotlib.pyplot; " + draw
    for code, backend in ((chosen, "pdf"), (draw, "agg")):
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
        assert out.stdout.strip().lower() == backend, out.stderr


def test_the_reports_tables_are_its_documents_entries(thesis_dir):
    report = pamkit.diagnose(thesis_dir.parent / "festo" / "DMSP-10-250.toml", threads=2)
    document = report.to_dict()
    candidates = report.candidates
    assert isinstance(candidates, pd.DataFrame) and len(candidates) == len(document["candidates"])
    assert list(candidates["effect"]) == [c["effect"] for c in document["candidates"]]
    assert list(candidates["score"]) == [c["score"] for c in document["candidates"]]
    assert list(candidates["gain.force_N"]) == [c["gain"]["force_N"] for c in document["candidates"]]
    # The cause named (slip_hysteresis on this map, README's Festo table) is the one row of causes.
    causes = report.causes
    assert report.cause not in ("none", "unexplained")
    assert list(causes["effect"]) == [report.cause] == document["extended"]["effects"]
    summary = report.channels_summary
    assert summary.loc["force_N", "gain"] == document["gain"]["force_N"]
    assert summary.loc["force_N", "baseline_rmse"] == document["baseline"]["heldout_rmse"]["force_N"]


def test_a_report_read_back_from_json_keeps_its_answers(tmp_path):
    report = pamkit.diagnose(SOURCE_DIR / "data" / "experiments" / "example" / "experiment.toml", threads=2)
    report.to_json(tmp_path / "report.json")
    again = pamkit.Report.read_json(tmp_path / "report.json")
    assert again.to_dict() == json.loads(report.to_json()) and again.verdict() == report.verdict()
    pd.testing.assert_frame_equal(again.candidates, report.candidates)
    with pytest.raises(ValueError, match="holds no predictions to draw"):
        again.plot(tmp_path / "again.png")
    with pytest.raises(ValueError, match="holds no predictions to draw"):
        again.figure()
    (tmp_path / "broken.json").write_text('{"cause": "none",\n  "baseline": }')
    with pytest.raises(ValueError, match=r"broken.json:2:15: not JSON"):
        pamkit.Report.read_json(tmp_path / "broken.json")
    (tmp_path / "other.json").write_text("[1, 2]")
    with pytest.raises(ValueError, match=r"other.json: not a pamkit diagnosis report"):
        pamkit.Report.read_json(tmp_path / "other.json")


def test_a_notebook_shows_the_verdict_and_the_ranking(thesis_dir):
    report = pamkit.diagnose(thesis_dir.parent / "festo" / "DMSP-10-250.toml", threads=2)
    shown = report._repr_html_()
    assert html.escape(report.verdict()) in shown
    assert "<table" in shown and "slip_hysteresis" in shown and f"{len(report.candidates)} candidates" in shown


def test_a_campaign_of_tables_is_one_report(thesis_dir):
    tables = [thesis_dir / "table_3_4_pam1.toml", thesis_dir / "table_3_4_pam2.toml"]
    report = pamkit.diagnose(tables, threads=2)
    assert report.kind == "free_inflation" and set(report.channels) == {"length_m", "diameter_m"}
    # README's validation: table 3.4 as a campaign is unexplained (the cone geometry's reach).
    assert report.cause == "unexplained" and report.causes.empty
    assert "unexplained" in report.verdict()


def test_the_calls_are_functions_and_the_modules_stay_importable():
    import pamkit.diagnosis.engine as engine  # `import a.b.c as d` looks b up on a: must be the module
    from pamkit.diagnosis import diagnose
    from pamkit.simulation import simulate_experiment as again

    assert again is simulate_experiment and engine.diagnose is diagnose
    for function in (pamkit.simulate, pamkit.diagnose):
        assert isinstance(function, types.FunctionType) and not isinstance(function, types.ModuleType)
    assert pamkit.simulate is pamkit.simulation.simulate
    assert "experiment_or_path" in inspect.signature(pamkit.simulate).parameters
    assert "path_or_experiments" in inspect.signature(pamkit.diagnose).parameters
    assert {"load_experiment", "simulate", "diagnose", "Report", "write_experiment"} <= set(pamkit.__all__)
    assert all(hasattr(pamkit, name) for name in pamkit.__all__)
    # help() shows a function's page, not a module's.
    assert pydoc.render_doc(pamkit.diagnose, renderer=pydoc.plaintext).splitlines()[2].startswith("diagnose(")


def test_an_experiment_goes_to_a_frame_and_back(tmp_path):
    experiment = pamkit.load_experiment(SOURCE_DIR / "data" / "experiments" / "example" / "experiment.toml")
    frame = experiment.to_frame()
    assert list(frame.columns) == list(experiment.columns) == SERIES_COLUMNS  # SI, as simulate's
    assert frame.attrs["units"]["gauge_pressure_Pa"] == "Pa" and frame.attrs["units"]["temperature_K"] == "K"
    assert frame.attrs["kind"] == "series" and frame.attrs["gas"] == "sealed"
    # The sections are a file's, in its units: the inflation pressure in kPa, the room in °C.
    sections = {
        "muscle": {"length_m": experiment.build.length_m, "diameter_m": experiment.build.diameter_m},
        "test": {
            "inflation_pressure_kPa": experiment.inflation_gauge_pressure_Pa / PASCAL_PER_KILOPASCAL,
            "ambient_temperature_C": experiment.gas_params.ambient_temperature_K - KELVIN_AT_ZERO_CELSIUS,
        },
    }
    again = pamkit.Experiment.from_frame(frame, tmp_path / "again.toml", sections)
    assert again.path == tmp_path / "again.toml" and again.data_path == tmp_path / "again.csv"
    assert again.inflation_gauge_pressure_Pa == pytest.approx(experiment.inflation_gauge_pressure_Pa, rel=1e-12)
    assert again.gas_params.ambient_temperature_K == pytest.approx(experiment.gas_params.ambient_temperature_K)
    for name, column in experiment.columns.items():
        # write_series keeps 10 significant digits
        np.testing.assert_allclose(again.columns[name], column, rtol=1e-9, atol=1e-12)
    # The file between them is in the file's units: kPa and °C, as a person reads it.
    header, first = (tmp_path / "again.csv").read_text().splitlines()[:2]
    written = dict(zip(header.split(","), map(float, first.split(","))))
    kilopascals = experiment.columns["gauge_pressure_Pa"][0] / PASCAL_PER_KILOPASCAL
    assert written["pressure_kPa"] == pytest.approx(kilopascals, rel=1e-9)
    assert written["temperature_C"] == pytest.approx(experiment.columns["temperature_K"][0] - KELVIN_AT_ZERO_CELSIUS)
    # What the reader refuses in a file it refuses from a frame, naming the file it wrote.
    with pytest.raises(ExperimentError, match=r"bad.csv.*time_s"):
        pamkit.Experiment.from_frame(frame.drop(columns=["time_s"]), tmp_path / "bad.toml", sections)
    with pytest.raises(ExperimentError, match=r"isotonic.toml: \[test\] load_N is missing"):
        pamkit.Experiment.from_frame(
            pd.DataFrame({"gauge_pressure_Pa": [0.0, 100e3], "length_m": [0.2, 0.19]}),
            tmp_path / "isotonic.toml",
            {"muscle": {}, "test": {"kind": "isotonic"}},
        )
    # A frame takes SI columns: a file's name for one is refused, naming the SI name to give.
    with pytest.raises(ValueError, match=r"kpa.toml: column pressure_kPa .* gauge_pressure_Pa"):
        pamkit.Experiment.from_frame(
            frame.rename(columns={"gauge_pressure_Pa": "pressure_kPa"}), tmp_path / "kpa.toml", sections
        )


def test_write_experiment_is_the_files_writer(tmp_path):
    data = pamkit.write_experiment(
        tmp_path / "map.toml",
        {"muscle": {"length_m": 0.25, "diameter_m": 0.01}, "test": {"kind": "isometric_map"}},
        {"length_m": np.array([0.25, 0.24]), "gauge_pressure_Pa": np.array([100e3, 200e3]), "force_N": [10.0, 40.0]},
    )
    assert data == tmp_path / "map.csv"
    assert data.read_text().splitlines()[:2] == ["length_m,pressure_kPa,force_N", "0.25,100,10"]  # the file's units
    again = pamkit.load_experiment(tmp_path / "map.toml")
    assert list(again.columns["force_N"]) == [10.0, 40.0]
    assert list(again.columns["gauge_pressure_Pa"]) == [100e3, 200e3]


@pytest.mark.parametrize(
    "name, says",
    [
        ("load_experiment", ["time_s [s]", "elongation_m [m]", "force_N [N]", "N (rows"]),
        ("simulate", ["time_s [s]", "force_N [N]", "gauge_pressure_Pa [Pa]", "N rows", "solver_statistics"]),
        ("diagnose", ["Report.verdict", "Report.candidates", "Report.causes", "Report.to_json", "Report.plot"]),
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


def test_the_readmes_python_runs(tmp_path, monkeypatch):
    # README.md's Python quickstart, as written, on the bundled data.
    text = (SOURCE_DIR / "README.md").read_text()
    script = text.split("```python\n", 1)[1].split("```", 1)[0]
    script = script.replace('"data/', f'"{SOURCE_DIR / "data"}/')
    monkeypatch.chdir(tmp_path)
    import matplotlib

    matplotlib.use("Agg")
    namespace: dict = {}
    exec(compile(script, "README.md", "exec"), namespace)
    assert namespace["report"].cause == "slip_hysteresis"  # the README's Festo line, which its comment quotes
    assert (tmp_path / "report.json").is_file() and (tmp_path / "report.png").read_bytes()[:4] == b"\x89PNG"


def test_a_narrow_interval_of_the_gain_is_printed_with_ends_that_differ():
    # The bundled example's heat transfer gains 0.974 with a 95 % interval 0.973-0.975: printed at
    # two decimals, both ends would read 0.97, a zero width the data never claimed.
    report = pamkit.diagnose(SOURCE_DIR / "data" / "experiments" / "example" / "experiment.toml", threads=2)
    document = report.to_dict()
    low, high = document["causes"][0]["gain_ci95"]["temperature_K"]
    match = re.search(r"\(gain ([0-9.]+), 95 % CI ([0-9.]+)–([0-9.]+)\)", report.verdict())
    assert match is not None, report.verdict()
    gain, printed_low, printed_high = match.groups()
    assert printed_low != printed_high
    digits = len(printed_low.split(".")[1])
    assert (printed_low, printed_high) == (f"{low:.{digits}f}", f"{high:.{digits}f}")
    assert float(printed_low) <= float(gain) <= float(printed_high)
