"""The Python face of the C++ core: exceptions, parameter structs, arrays, threads."""

from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import pamkit
from pamkit.effects import parse_effects


def test_invalid_parameter_is_a_value_error_naming_the_field():
    with pytest.raises(ValueError, match=r"MuscleBuild\.fiber_count = -3"):
        pamkit.MuscleBuild(fiber_count=-3).validate()
    with pytest.raises(ValueError, match=r"GasParams\.polytropic_index"):
        pamkit.MuscleModel(pamkit.MuscleParams(gas=pamkit.GasParams(polytropic_index=2.0)), pamkit.InitialState())


def test_unknown_keyword_is_rejected():
    with pytest.raises(TypeError, match="MuscleBuild has no field 'fibre_count'"):
        pamkit.MuscleBuild(fibre_count=3)


def test_fields_list_units_and_ranges():
    fields = pamkit.MuscleBuild.fields()
    assert fields["length_m"]["unit"] == "m"
    assert set(fields) == set(pamkit.MuscleBuild().to_dict())
    assert "fiber_count=216" in repr(pamkit.MuscleBuild())


def test_trajectory_rejects_time_going_back():
    with pytest.raises(ValueError, match=r"time_s\[2\] = 1 does not increase"):
        pamkit.ElongationTrajectory(np.array([0.0, 1.0, 1.0]), np.zeros(3))
    with pytest.raises(ValueError, match="1-D"):
        pamkit.ElongationTrajectory(np.zeros((2, 2)), np.zeros((2, 2)))


def test_results_are_read_only_views_that_outlive_their_run():
    model = pamkit.MuscleModel(pamkit.MuscleParams(), pamkit.InitialState())
    force = pamkit.Simulator().run(model, pamkit.thesis_protocol(0.05, cycles=1)).force_N
    assert not force.flags.writeable
    with pytest.raises(ValueError):
        force[0] = 0.0
    assert np.all(np.isfinite(force)) and force.max() > force[0]


def test_runs_in_threads_match_serial_runs():
    simulator = pamkit.Simulator()
    models = [
        pamkit.MuscleModel(pamkit.MuscleParams(), pamkit.InitialState(gauge_pressure_Pa=p))
        for p in (150e3, 200e3, 250e3, 300e3)
    ]
    trajectory = pamkit.thesis_protocol(0.05, cycles=2)
    serial = [simulator.run(m, trajectory).force_N.copy() for m in models]
    with ThreadPoolExecutor(max_workers=4) as pool:
        parallel = list(pool.map(lambda m: simulator.run(m, trajectory).force_N.copy(), models))
    for a, b in zip(serial, parallel):
        np.testing.assert_array_equal(a, b)


def test_integration_method_is_a_field_and_the_statistics_name_the_method_that_ran():
    config = pamkit.SimulatorConfig(method=pamkit.IntegrationMethod.auto)
    assert config.method == pamkit.IntegrationMethod.auto and "method=auto" in repr(config)
    assert config.to_dict()["method"] == pamkit.IntegrationMethod.auto
    assert pamkit.SimulatorConfig().method == pamkit.IntegrationMethod.bdf  # the default stays BDF
    with pytest.raises(TypeError):
        pamkit.SimulatorConfig(method="adams")  # an IntegrationMethod, not a string
    # A gas exchanging heat in 5 s along 20.9 s ramps: 0.2 /s x 20.9 s x (1e-8)^(1/6) = 0.19 < 1, not stiff.
    gas = pamkit.GasParams(process=pamkit.GasProcess.heat_transfer, heat_transfer_time_constant_s=5.0)
    model = pamkit.MuscleModel(pamkit.MuscleParams(gas=gas), pamkit.InitialState())
    trajectory = pamkit.thesis_protocol(0.0523, cycles=1)
    estimate = pamkit.estimate_stiffness(model, trajectory, config)
    assert estimate.ratio == pytest.approx(0.2 * 20.92 * 1e-8 ** (1 / 6), rel=1e-12) and not estimate.stiff
    assert pamkit.Simulator(config).run(model, trajectory).statistics.method == pamkit.IntegrationMethod.dopri5
    assert pamkit.Simulator().run(model, trajectory).statistics.method == pamkit.IntegrationMethod.bdf


def test_an_instrument_reads_a_measurement_into_a_new_one_and_leaves_it_as_it_was():
    # The diagnosis hands one simulated run to every instrument it tries (a load cell's offset, a
    # transducer's lag) without copying it first: each must return its reading and leave the run.
    run = pamkit.Measurement()
    run.time_s = np.linspace(0.0, 1.0, 11)
    run.elongation_m = np.linspace(0.0, 0.01, 11)
    run.force_N = np.linspace(0.0, 100.0, 11)
    run.gauge_pressure_Pa = np.linspace(1e5, 2e5, 11)
    run.temperature_K = np.full(11, 293.15)
    before = {name: np.array(getattr(run, name)) for name in ("force_N", "gauge_pressure_Pa", "temperature_K")}
    for spec in (
        "load_cell:offset_N=5",
        "sensor_offset:offset_Pa=2000",
        "sensor_lag:channel=force_N,time_constant_s=0.2",
    ):
        read = parse_effects([spec])[0].apply_to_measurement(run)
        assert any(not np.array_equal(getattr(read, c), before[c]) for c in before), spec
        assert all(np.array_equal(getattr(run, c), before[c]) for c in before), spec


def test_an_effects_motion_and_supplied_pressure_are_arrays_in_and_out():
    # The diagnosis moves the muscle by a fixture's play once for every point of a fit's Jacobian:
    # the arrays pass through their buffers, as every other run's do, and come back as arrays.
    time_s = np.linspace(0.0, 20.0, 2001)
    crosshead_m = 0.02 * np.sin(time_s)
    (slack,) = parse_effects(["fixture_slack:slack_m=0.002"])
    moved = slack.apply_to_elongation(time_s, crosshead_m)
    assert isinstance(moved, np.ndarray) and moved.shape == time_s.shape
    assert np.array_equal(moved, slack.apply_to_elongation(list(time_s), list(crosshead_m)))
    # The play as a backlash written here: the muscle follows the crosshead's leading edge and
    # rests within the play of it while the crosshead turns (from the crosshead's first value).
    position, expected = crosshead_m[0], []
    for x in crosshead_m:
        position = min(max(position, x - 0.002), x)
        expected.append(position)
    assert np.array_equal(moved, expected)

    (offset,) = parse_effects(["sensor_offset:offset_Pa=2000"])
    reading_Pa = np.array([101e3, 150e3, 250e3])
    driving = offset.apply_to_supplied_pressure([], reading_Pa)  # no times: a table's settled rows
    assert isinstance(driving, np.ndarray)
    np.testing.assert_allclose(driving, reading_Pa - 2000.0, rtol=0, atol=1e-9)
