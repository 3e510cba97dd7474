"""Units at the edges: a file is read in the units a person writes (kPa gauge, °C) and converted
once, by the reader, to SI; every API below it (Experiment, the simulation, the model) is SI,
the room's temperature is one fact (gas_params.ambient_temperature_K), the gas mode an enum,
and a sealed test starts from one builder (pamkit.simulation.sealed_start).

The factors are SI's definitions: 1 kPa = 1000 Pa, T [K] = T [°C] + 273.15."""

import json

import numpy as np
import pytest

import pamkit
from pamkit.io.experiment import load_experiment
from pamkit.io.guards import ExperimentError
from pamkit.io.series import read_series
from pamkit.io.writers import write_series
from pamkit.simulation import muscle_params, sealed_start, simulate_experiment
from pamkit.sweep import with_parameters
from pamkit.synth.dataset import synthesize

FILE = "time_s,elongation_m,force_N,pressure_kPa,temperature_C\n0,0,12.5,236.63,22.85\n0.5,0.001,13.25,240.5,23.1\n"


def test_a_file_is_read_in_si_and_written_back_as_it_was(tmp_path):
    path = tmp_path / "run.csv"
    path.write_text(FILE)
    columns = read_series(path)
    assert list(columns) == ["time_s", "elongation_m", "force_N", "gauge_pressure_Pa", "temperature_K"]
    np.testing.assert_array_equal(columns["gauge_pressure_Pa"], [236.63 * 1000, 240.5 * 1000])
    np.testing.assert_array_equal(columns["temperature_K"], [22.85 + 273.15, 23.1 + 273.15])
    again = tmp_path / "again.csv"
    write_series(again, columns)
    # The writer's format (CRLF, 10 significant digits) gives the person's numbers back.
    assert again.read_text().replace("\r\n", "\n") == FILE


def test_the_room_is_one_fact_that_the_model_reads(write_experiment):
    experiment = load_experiment(
        write_experiment(
            csv_text="time_s,elongation_m,pressure_kPa\n0,0,200\n1,0.001,210\n2,0.002,220\n",
            toml_test_extra='gas = "supplied"',
        )
    )
    assert not hasattr(experiment, "ambient_temperature_C")
    assert experiment.gas_params.ambient_temperature_K == 22.85 + 273.15  # the file's 22.85 °C
    assert experiment.gas == pamkit.GasMode.supplied
    # A supplied test's gas stays at the room's temperature: the channel is that one fact.
    np.testing.assert_array_equal(
        simulate_experiment(experiment)["temperature_K"], [experiment.gas_params.ambient_temperature_K] * 3
    )
    experiment.gas_params.ambient_temperature_K = 300.0
    np.testing.assert_array_equal(simulate_experiment(experiment)["temperature_K"], [300.0] * 3)


def test_a_gas_mode_the_file_misspells_is_named(write_experiment):
    with pytest.raises(ExperimentError, match=r"run.toml: \[test\] gas = 'seald' must be one of sealed, supplied"):
        load_experiment(write_experiment(toml_test_extra='gas = "seald"'))


def test_a_sealed_start_is_the_muscle_inflated_freely_and_sealed(write_experiment):
    # PAM 2 inflated with nothing on its ends settles where it carries no force; sealed there, it
    # starts the test at the file's inflation pressure.
    path = write_experiment()
    path.write_text(path.read_text().replace("initial_length_m = 0.167\n", ""))
    experiment = load_experiment(path)
    params = muscle_params(experiment)
    start = sealed_start(experiment, params)
    assert start.gauge_pressure_Pa == experiment.inflation_gauge_pressure_Pa == 236.63e3
    free = pamkit.static_forces(params, [start.length_m], [start.gauge_pressure_Pa])[0]
    assert abs(free) < 1e-6  # N: the free-inflation solve's tolerance on a force of hundreds
    # A calibrated pressure moves the start; a declared initial length holds the length.
    moved = sealed_start(experiment, params, 240e3)
    assert moved.gauge_pressure_Pa == 240e3 and moved.length_m < start.length_m  # more gas, shorter
    held = sealed_start(load_experiment(write_experiment()), params, 240e3)
    assert (held.length_m, held.gauge_pressure_Pa) == (0.167, 240e3)
    # The simulation starts there: at t = 0 the gas is at the inflation pressure (the ideal gas
    # law forward and back, to rounding).
    first = simulate_experiment(experiment)["gauge_pressure_Pa"][0]
    assert first == pytest.approx(236.63e3, rel=1e-12)


def test_a_synthetic_test_starts_where_a_reader_of_its_file_starts(tmp_path):
    # synth simulates the truth from the state a diagnosis of its file will start from: the
    # reader's, built by sealed_start, bit for bit.
    files = synthesize("none", 3, tmp_path / "none")
    experiment = load_experiment(files.experiment)
    start = sealed_start(experiment, muscle_params(experiment))
    protocol = json.loads(files.manifest.read_text())["protocol"]
    assert start.length_m == protocol["free_length_m"]
    assert start.gauge_pressure_Pa == protocol["inflation_pressure_kPa"] * 1000


def test_a_sweep_sets_the_tests_conditions_as_a_file_gives_them(thesis_dir):
    base = load_experiment(thesis_dir / "pam2_207kPa_80pct.toml")
    swept = with_parameters(base, {"inflation_pressure_kPa": 150.0, "ambient_temperature_C": 30.0})
    assert swept.inflation_gauge_pressure_Pa == 150e3
    assert swept.gas_params.ambient_temperature_K == 30.0 + 273.15
    assert base.inflation_gauge_pressure_Pa == 218.98e3  # table C.2's 80 % test, left as it was
