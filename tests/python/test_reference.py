"""The reference (pamkit.reference, from which the documentation's reference pages and `pamkit
template` are generated) against the readers: every section, key and column they take is
documented, with the kinds of test that take it and need it as the readers decide them, and each
template is a file they read."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import tomllib

import pamkit
from pamkit.cli import command_help, main
from pamkit.io.columns import OTHER_UNITS, file_name
from pamkit.io.experiment import load_experiment, load_tests
from pamkit.io.guards import ExperimentError
from pamkit.io.schema import CAMPAIGN_SECTIONS, TEST_KEYS
from pamkit.reference import (
    KINDS,
    SERIES_KINDS,
    SUPPLIED,
    TEST_KEY_MEANINGS,
    data_columns,
    experiment_keys,
    params_file_keys,
)
from pamkit.templates import TEMPLATE_KINDS, template

SECTIONS = ("muscle", "bladder", "friction", "gas", "calibrate", "uncertain", "test")

# Rows each kind's data CSV may hold, made to be read (not to be physical beyond it): a short
# stretch of PAM 2 for a time series, a few settled rows of a 10 mm datasheet muscle for a table.
ROWS = {
    "sealed": "time_s,elongation_m,force_N\n0,0,1\n1,0.001,2\n2,0.002,3\n",
    "supplied": "time_s,elongation_m,pressure_kPa\n0,0,0\n1,0,50\n2,0,100\n",
    "isometric_map": "length_m,pressure_kPa,force_N\n0.25,100,50\n0.24,200,80\n0.23,300,90\n",
    "isotonic": "time_s,pressure_kPa,length_m\n0,0,0.25\n1,200,0.24\n2,400,0.23\n",
    "free_inflation": "pressure_kPa,length_m,diameter_m\n35,0.2,0.027\n69,0.19,0.028\n104,0.18,0.029\n",
}
# A value for each [test] key that the reader takes where the key belongs.
VALUES = {
    "inflation_pressure_kPa": 100.0,
    "ambient_temperature_C": 20.0,
    "kind": None,  # the kind's own, set by the template
    "gas": None,
    "initial_length_m": 0.2,
    "load_N": 100.0,
    "load_mass_kg": 10.0,
    "description": "a test",
    "zero": "zero.csv",
    "preload_N": 20.0,
    "force_range_N": [-5.0, 1500.0],
    "pressure_range_kPa": [-10.0, 1000.0],
    "specimen": "1",
    "ignore_columns": ["note"],
    "glitches": "keep",
    "data": "run.csv",
}


def written(tmp_path: Path, kind: str, test_changes: dict | None = None, drop: str | None = None) -> Path:
    """The kind's template with its rows, [test] changed by `test_changes` and key `drop` removed."""
    document = tomllib.loads(template(kind))
    test = document.setdefault("test", {})
    for key, value in (test_changes or {}).items():
        test[key] = value
    if drop is not None:
        test.pop(drop, None)
    (tmp_path / "run.csv").write_text(ROWS[kind])
    (tmp_path / "zero.csv").write_text("time_s,elongation_m,force_N,pressure_kPa\n0,0,0.5,0.2\n1,0,0.4,0.1\n")
    path = tmp_path / f"{kind}.toml"
    lines = []
    for section, table in document.items():
        lines.append(f"[{section}]")
        for key, value in table.items():
            if isinstance(value, dict):  # [calibrate] bladder.shear_modulus_Pa
                lines += [f"{key}.{inner} = {_toml(bounds)}" for inner, bounds in value.items()]
            else:
                lines.append(f"{key} = {_toml(value)}")
    path.write_text("\n".join(lines) + "\n")
    return path


def _toml(value) -> str:
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return repr(value)


def known_list(message: str) -> set[str]:
    """The names a reader's "unknown ..." error lists as known."""
    return {name.strip() for name in re.search(r"\(known: ([^)]*)\)", message).group(1).split(",")}


def documented(section: str) -> set[str]:
    return {key.name for key in experiment_keys() if key.section == section}


@pytest.mark.parametrize("kind", KINDS)
def test_every_template_is_a_file_the_reader_takes(tmp_path, kind):
    experiment = load_experiment(written(tmp_path, kind))
    expected_kind = "series" if kind in SERIES_KINDS else kind
    assert experiment.kind == expected_kind
    assert experiment.gas == (pamkit.GasMode.sealed if kind == "sealed" else pamkit.GasMode.supplied)
    # The reference's name inside pamkit of each column the file gives is the experiment's own.
    header = ROWS[kind].splitlines()[0].split(",")
    assert set(experiment.columns) == {c.si_name for c in data_columns(kind) if c.name in header}
    # ... and one the model predicts.
    frame = pamkit.simulate(experiment)
    assert len(frame) == len(ROWS[kind].splitlines()) - 1 and np.isfinite(frame.to_numpy()).all()


def test_the_campaign_template_names_its_tests_and_shares_its_muscle(tmp_path):
    path = tmp_path / "campaign.toml"
    path.write_text(template("campaign"))
    for name in ("test_1", "test_2"):
        document = tomllib.loads(template("sealed"))
        del document["muscle"]  # the campaign gives it
        (tmp_path / "run.csv").write_text(ROWS["sealed"])
        (tmp_path / f"{name}.toml").write_text(
            "[test]\n" + "\n".join(f"{k} = {_toml(v)}" for k, v in document["test"].items()) + "\n"
        )
    tests = load_tests(path)
    assert [t.path.name for t in tests] == ["test_1.toml", "test_2.toml"]
    assert {t.build.length_m for t in tests} == {tomllib.loads(template("campaign"))["muscle"]["length_m"]}


@pytest.mark.parametrize("section", ["muscle", "friction", "gas", "bladder", "calibrate", "uncertain", "test"])
def test_every_key_a_section_takes_is_documented(tmp_path, section):
    path = written(tmp_path, "sealed")
    text = path.read_text().replace(f"[{section}]\n", f"[{section}]\nno_such_key = 1\n")
    if f"[{section}]" not in text:
        text += f"\n[{section}]\nno_such_key = 1\n"
    path.write_text(text)
    with pytest.raises(ExperimentError, match="no_such_key") as error:
        load_experiment(path)
    known = known_list(str(error.value))
    # [muscle] names braid_angle_deg (it stands for fiber_revolutions) and construction among them.
    assert known <= documented(section), f"[{section}] takes keys the reference does not document"
    assert documented(section) == known


def test_the_sections_and_test_keys_are_the_readers(tmp_path):
    path = written(tmp_path, "sealed")
    path.write_text(path.read_text() + "\n[no_such_section]\n")
    with pytest.raises(ExperimentError, match="no_such_section") as error:
        load_experiment(path)
    assert known_list(str(error.value)) == set(SECTIONS)
    assert documented("test") == set(TEST_KEYS) == set(TEST_KEY_MEANINGS)
    assert CAMPAIGN_SECTIONS[0] == "campaign" and documented("campaign") == {"tests"}


@pytest.mark.parametrize("kind", KINDS)
def test_the_kinds_each_test_key_belongs_to_are_the_readers(tmp_path, kind):
    """A key documented as not for a kind is refused there, naming the key; one documented as
    required is missed there, naming the key; the others are taken."""
    for key in (k for k in experiment_keys() if k.section == "test"):
        folder = tmp_path / key.name
        folder.mkdir()
        value = VALUES[key.name]
        if key.name == "preload_N":  # the preload sets the length a supplied test starts at
            value_changes = {key.name: value}
            drop = "initial_length_m"
        else:
            value_changes = {} if value is None else {key.name: value}
            drop = None
        if kind not in key.kinds:
            with pytest.raises(ExperimentError, match=key.name):
                load_experiment(written(folder, kind, value_changes, drop))
            continue
        # specimen is taken with a tensile machine's export of several specimens
        # (test_machine_specimens.py), which these rows are not.
        if value is not None and key.name != "specimen":
            load_experiment(written(folder, kind, value_changes, drop))
        if kind in key.required:
            with pytest.raises(ExperimentError, match=rf"{key.name}.* missing|missing .*{key.name}"):
                load_experiment(written(folder, kind, drop=key.name))


@pytest.mark.parametrize("kind", KINDS)
def test_each_required_column_is_required(tmp_path, kind):
    columns = data_columns(kind)
    header = ROWS[kind].splitlines()[0].split(",")
    assert {c.name for c in columns if c.required} <= set(header)
    for column in (c for c in columns if c.required):
        kept = [i for i, name in enumerate(header) if name != column.name]
        rows = [",".join(line.split(",")[i] for i in kept) for line in ROWS[kind].splitlines()]
        path = written(tmp_path, kind)
        (tmp_path / "run.csv").write_text("\n".join(rows) + "\n")
        with pytest.raises(ExperimentError, match=column.name):
            load_experiment(path)
    # A time series takes the measured channels pamkit predicts, as a file names them, and nothing else.
    if kind == SUPPLIED:
        channels = pamkit.measured_channels()
        assert [c.name for c in columns] == ["time_s", "elongation_m", *(file_name(c) for c in channels)]
        assert [c.si_name for c in columns] == ["time_s", "elongation_m", *channels]


def test_the_python_names_the_reference_gives_hold_the_files_values_in_si(tmp_path):
    # The reference names a [test] key as a file gives it and, where pamkit converts it, the SI
    # attribute of Experiment that holds it: that attribute holds the file's value, converted
    # (1 kPa = 1000 Pa; 0 °C = 273.15 K, by the units' definitions).
    path = written(tmp_path, "sealed", {"pressure_range_kPa": [-10.0, 1000.0]})
    test = tomllib.loads(path.read_text())["test"]
    experiment = load_experiment(path)
    expected = {
        "inflation_pressure_kPa": test["inflation_pressure_kPa"] * 1e3,
        "ambient_temperature_C": test["ambient_temperature_C"] + 273.15,
        "pressure_range_kPa": (-10e3, 1000e3),
    }
    named = {}
    for key in (k for k in experiment_keys() if k.section == "test"):
        match = re.search(r"Experiment\.([\w.]+)(?:\['(\w+)'\])?", key.meaning)
        if match:
            value = experiment
            for attribute in match.group(1).split("."):
                value = getattr(value, attribute)
            named[key.name] = value[match.group(2)] if match.group(2) else value
    assert set(named) == set(expected)
    for name, value in expected.items():
        assert named[name] == pytest.approx(value, rel=1e-12), name


@pytest.mark.parametrize("neo_hookean", [False, True])
def test_the_parameters_files_keys_are_documented(tmp_path, neo_hookean):
    params = pamkit.MuscleParams()
    if neo_hookean:
        params.bladder = pamkit.BladderLaw.neo_hookean(1e6)
    pamkit.write_muscle_params(tmp_path / "muscle.toml", params, pamkit.InitialState(), rig_effects=["time_skew"])
    document = tomllib.loads((tmp_path / "muscle.toml").read_text())
    written_keys = {(section, key) for section, table in document.items() for key in table}
    reference = {(k.section, k.name) for k in params_file_keys()}
    assert written_keys <= reference
    # Every documented key but the other bladder form's is written.
    other_form = {"longitudinal_Pa", "hoop_Pa"} if neo_hookean else {"shear_modulus_Pa"}
    assert reference - written_keys == {("bladder", name) for name in other_form}


def test_the_command_line_reference_holds_every_command():
    commands = dict(command_help())
    for name in ("simulate", "diagnose", "synth", "effects", "exo", "log", "align", "flash", "sweep", "template"):
        assert f"pamkit {name}" in commands and commands[f"pamkit {name}"].startswith(f"usage: pamkit {name}")
    assert "--version" in commands["pamkit"]


def test_pamkit_template_writes_the_toml_and_the_csvs_header(tmp_path, capsys):
    assert main(["template", "isotonic", "-o", str(tmp_path / "iso.toml")]) == 0
    assert (tmp_path / "iso.toml").read_text() == template("isotonic", data="iso.csv")
    assert (tmp_path / "iso.csv").read_text() == "pressure_kPa,length_m\n"
    assert main(["template", "isotonic", "-o", str(tmp_path / "iso.toml")]) == 2  # it would overwrite
    assert "iso.toml exists" in capsys.readouterr().err
    assert main(["template", "isotonic", "-o", str(tmp_path / "iso.toml"), "--force"]) == 0
    capsys.readouterr()
    assert main(["template", "sealed"]) == 0
    assert capsys.readouterr().out == template("sealed")
    assert set(TEMPLATE_KINDS) == {*KINDS, "campaign"}


def test_pamkit_version_is_the_projects():
    # The version is kept in CMakeLists.txt's project() alone.
    source = Path(pamkit.__file__).resolve().parents[3]
    cmake = Path(__import__("os").environ.get("PAMKIT_SOURCE_DIR", source)) / "CMakeLists.txt"
    declared = re.search(r"project\(pamkit VERSION ([0-9.]+)", cmake.read_text()).group(1)
    assert pamkit.__version__ == declared
    with pytest.raises(SystemExit) as done:
        main(["--version"])
    assert done.value.code == 0


def test_every_other_unit_a_reader_takes_is_in_the_data_columns_page():
    page = (Path(__file__).resolve().parents[2] / "docs" / "reference" / "data-columns.rst").read_text()
    missing = [unit.file_name for unit in OTHER_UNITS if f"``{unit.file_name}``" not in page]
    assert not missing, f"docs/reference/data-columns.rst does not name {missing}"
