"""Simulator.run_batch from Python: numpy arrays of one row per run, each run Simulator.run's bit
for bit whatever the number of threads, a failed run alone NaN with its message, and ParameterSets
making the muscle a caller would make by hand."""

import numpy as np
import pytest

import pamkit

TRAJECTORY = pamkit.thesis_protocol(0.04, cycles=2)
CHANNELS = ["force_N", "gauge_pressure_Pa", "temperature_K", "heat_lost_J"]


def muscle(pressure_Pa: float, tau_s: float, length_m: float = 0.167) -> pamkit.MuscleModel:
    params = pamkit.MuscleParams()
    params.gas.process = pamkit.GasProcess.heat_transfer
    params.gas.heat_transfer_time_constant_s = tau_s
    return pamkit.MuscleModel(params, pamkit.InitialState(length_m=length_m, gauge_pressure_Pa=pressure_Pa))


MODELS = [muscle(120e3 + 20e3 * i, 0.5 + i) for i in range(7)]


@pytest.mark.parametrize("method", ["bdf", "rosenbrock4", "auto"])
def test_each_run_is_simulator_run_bit_for_bit(method):
    simulator = pamkit.Simulator(pamkit.SimulatorConfig(method=getattr(pamkit.IntegrationMethod, method)))
    rows = np.arange(0, len(TRAJECTORY), 9)
    batch = simulator.run_batch(MODELS, TRAJECTORY, channels=CHANNELS, rows=rows, threads=3)
    assert batch.runs == len(MODELS) and batch.channels == CHANNELS
    np.testing.assert_array_equal(batch.rows, rows)
    for name in CHANNELS:
        assert batch.values[name].shape == (len(MODELS), len(rows))
        assert batch.maximum[name].shape == (len(MODELS),)
    assert not batch.failed.any() and batch.errors == [""] * len(MODELS)
    for i, model in enumerate(MODELS):
        run = simulator.run(model, TRAJECTORY)
        for name in CHANNELS:
            column = np.asarray(getattr(run, name))
            np.testing.assert_array_equal(batch.values[name][i], column[rows])
            assert batch.maximum[name][i] == column.max() and batch.minimum[name][i] == column.min()
        for counter in ("steps", "rhs_evaluations", "output_evaluations", "jacobian_evaluations", "restarts"):
            assert batch.statistics[counter][i] == getattr(run.statistics, counter)
        assert pamkit.IntegrationMethod(batch.statistics["method"][i]) == run.statistics.method
    # The runs differ: equal rows are not a property of the inputs.
    assert len(set(batch.maximum["force_N"])) == len(MODELS)


def test_the_number_of_threads_changes_no_number():
    simulator = pamkit.Simulator()
    rows = np.arange(len(TRAJECTORY))
    one = simulator.run_batch(MODELS, TRAJECTORY, channels=CHANNELS, rows=rows, threads=1)
    for threads in (2, 4, 0):
        other = simulator.run_batch(MODELS, TRAJECTORY, channels=CHANNELS, rows=rows, threads=threads)
        for name in CHANNELS:
            np.testing.assert_array_equal(other.values[name], one.values[name])
            np.testing.assert_array_equal(other.maximum[name], one.maximum[name])
        np.testing.assert_array_equal(other.statistics["steps"], one.statistics["steps"])


def test_a_failed_run_is_nan_with_its_message_and_the_others_run():
    # PAM 2's fibres are 0.258 m long: mounted at 0.24 m and stretched 4 cm more, the braid cannot follow.
    models = [MODELS[0], muscle(200e3, 2.0, length_m=0.24), MODELS[1]]
    batch = pamkit.Simulator().run_batch(models, TRAJECTORY, rows=[0, 10])
    np.testing.assert_array_equal(batch.failed, [False, True, False])
    assert "braid" in batch.errors[1] and not batch.rejected.any()
    assert pamkit.RunFailure(batch.failures[1]) == pamkit.RunFailure.input
    assert np.isnan(batch.values["force_N"][1]).all() and np.isnan(batch.maximum["force_N"][1])
    assert batch.statistics["steps"][1] == 0
    assert np.isfinite(batch.values["force_N"][[0, 2]]).all()


def test_the_arrays_are_read_only_views_that_keep_the_result_alive():
    values = pamkit.Simulator().run_batch(MODELS[:2], TRAJECTORY, rows=[3]).values["force_N"]
    assert not values.flags.writeable
    with pytest.raises(ValueError):
        values[0, 0] = 1.0
    assert np.isfinite(values).all()  # the result it views is gone from Python's names, not freed


def test_bad_requests_are_refused_by_name():
    simulator = pamkit.Simulator()
    with pytest.raises(ValueError, match="unknown channel 'torque_Nm'"):
        simulator.run_batch(MODELS, TRAJECTORY, channels=["torque_Nm"])
    with pytest.raises(ValueError, match="does not increase"):
        simulator.run_batch(MODELS, TRAJECTORY, rows=[5, 2])
    with pytest.raises(ValueError, match="1 motions for 7 models"):
        simulator.run_batch(MODELS, TRAJECTORY, motions=[TRAJECTORY])


def test_parameter_sets_make_the_muscle_a_caller_makes_by_hand():
    base = pamkit.MuscleParams()
    start = pamkit.InitialState(length_m=0.167, gauge_pressure_Pa=207e3)
    names = ["initial.gauge_pressure_Pa", "build.braid_angle_deg", "gas.ambient_temperature_K"]
    values = np.array([[150e3, 30.0, 290.0], [250e3, 33.0, 300.0], [200e3, 0.0, 296.0]])
    sets = pamkit.ParameterSets(base, start, names, values)
    assert sets.runs == 3 and sets.names == names
    params, initial = sets.at(1)
    build = pamkit.MuscleBuild()
    assert params.build.fiber_revolutions == pamkit.fiber_revolutions_for_braid_angle(build, 33.0)
    assert params.gas.ambient_temperature_K == 300.0 and initial.gauge_pressure_Pa == 250e3
    with pytest.raises(ValueError, match="braid_angle_deg = 0"):
        sets.at(2)
    with pytest.raises(IndexError):
        sets.at(3)

    simulator = pamkit.Simulator()
    batch = simulator.run_batch(sets, TRAJECTORY, rows=[0, 100], threads=2)
    np.testing.assert_array_equal(batch.rejected, [False, False, True])
    for i in (0, 1):
        run = simulator.run(pamkit.MuscleModel(*sets.at(i)), TRAJECTORY)
        np.testing.assert_array_equal(batch.values["force_N"][i], np.asarray(run.force_N)[[0, 100]])
        assert batch.maximum["gauge_pressure_Pa"][i] == max(run.gauge_pressure_Pa)
    with pytest.raises(ValueError, match="not a field a run can set"):
        pamkit.ParameterSets(base, start, ["build.colour"], np.ones((1, 1)))
    with pytest.raises(ValueError, match="one column per name"):
        pamkit.ParameterSets(base, start, names, np.ones((2, 2)))
