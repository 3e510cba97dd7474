"""The muscle-parameters file from Python: the C++ reader and writer (pamkit/io/params_file.hpp)
through the bindings, and `pamkit simulate --params`."""

import numpy as np
import pytest

import pamkit
from pamkit.cli import main
from pamkit.io.experiment import load_experiment
from pamkit.simulation import muscle_params


def read_force(path):
    return np.genfromtxt(path, delimiter=",", names=True)["force_N"]


def test_written_params_read_back_as_the_same_doubles(tmp_path):
    params = pamkit.MuscleParams()
    params.friction.fiber_fiber_coefficient = 0.2 * 2.718281828459045  # as a calibration scales it
    params.bladder = pamkit.BladderLaw.neo_hookean(1.0 / 3.0 * 1e6)
    params.gas.process = pamkit.GasProcess.heat_transfer
    params.extensions.slack_band_N = 0.1
    initial = pamkit.InitialState(length_m=0.1671234567, gauge_pressure_Pa=240123.4567)
    path = tmp_path / "calibrated.toml"
    pamkit.write_muscle_params(path, params, initial, comment="from a test")
    read = pamkit.read_muscle_params_file(path)
    for part in ("build", "friction", "gas", "extensions"):
        assert getattr(read.params, part).to_dict() == getattr(params, part).to_dict()
    assert read.params.gas.process == pamkit.GasProcess.heat_transfer
    assert read.params.bladder.form == pamkit.BladderLaw.Form.neo_hookean
    assert read.params.bladder.shear_modulus_Pa == params.bladder.shear_modulus_Pa
    assert read.initial.to_dict() == initial.to_dict()
    assert pamkit.read_muscle_params(str(path)).friction.to_dict() == params.friction.to_dict()
    assert path.read_text().startswith("# from a test\n")


def test_a_bad_file_is_a_value_error_naming_file_line_column_and_key(tmp_path):
    path = tmp_path / "bad.toml"
    pamkit.write_muscle_params(path, pamkit.MuscleParams())
    lines = path.read_text().splitlines()
    row = next(i for i, line in enumerate(lines) if line.startswith("leak_rate_per_s ="))
    lines[row] = "leak_rate_per_s = -1.0"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=rf"{path}:{row + 1}:19: \[extensions\] leak_rate_per_s: .*outside"):
        pamkit.read_muscle_params(path)


def test_simulate_with_params_uses_the_files_muscle(write_experiment, tmp_path):
    """The thesis's defaults written out and read back simulate exactly as the experiment's own
    [muscle] does; friction doubled in the file changes the force while stretching."""
    experiment = write_experiment("time_s,elongation_m\n0,0\n1,0.0025\n2,0.005\n3,0.0025\n4,0\n")
    params = muscle_params(load_experiment(experiment))
    same, rougher = tmp_path / "same.toml", tmp_path / "rougher.toml"
    pamkit.write_muscle_params(same, params)
    params.friction.fiber_fiber_coefficient *= 2
    params.friction.fiber_bladder_coefficient *= 2
    pamkit.write_muscle_params(rougher, params)
    forces = {}
    for name, arguments in {
        "own": [],
        "same": ["--params", same],
        "rougher": ["--params", rougher],
    }.items():
        output = tmp_path / f"{name}.csv"
        assert main(["simulate", str(experiment), *map(str, arguments), "-o", str(output)]) == 0
        forces[name] = read_force(output)
    assert (forces["same"] == forces["own"]).all()
    assert (forces["rougher"] != forces["own"]).any()


def test_simulate_with_a_bad_params_file_is_one_line_naming_it(write_experiment, tmp_path, capsys):
    experiment = write_experiment()
    bad = tmp_path / "bad.toml"
    bad.write_text("[build]\nlength_m = 0.2\n")
    assert main(["simulate", str(experiment), "--params", str(bad), "-o", str(tmp_path / "out.csv")]) == 2
    error = capsys.readouterr().err
    assert error.startswith(f"pamkit simulate: error: {bad}:1:1: missing key [build] diameter_m")
