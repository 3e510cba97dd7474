"""The diagnosis's Predictor: an instrument's finite-difference columns read the model's last run
(python/pamkit/diagnosis/series/model.py, Predictor.measurement) instead of simulating again. The numbers
must be a full run's, bit for bit, and only instruments may skip the run."""

import numpy as np
import pytest

import pamkit
import pamkit.diagnosis.series.model as model
from pamkit.diagnosis.series.model import Predictor
from pamkit.effects import parse_effects
from pamkit.io.experiment import load_experiment

CHANNELS = ["force_N", "gauge_pressure_Pa", "temperature_K"]


@pytest.fixture
def runs(monkeypatch):
    """Counts the model's sealed and supplied runs."""
    count = {"runs": 0}
    for name in ("simulate_measurement", "simulate_supplied_measurement"):
        real = getattr(model, name)

        def counted(*args, _real=real, **kwargs):
            count["runs"] += 1
            return _real(*args, **kwargs)

        monkeypatch.setattr(model, name, counted)
    return count


def sealed(write_experiment):
    rows = "\n".join(f"{0.1 * k:.1f},{0.0025 * min(k, 40 - k) * 0.1:.6f}" for k in range(41))
    return Predictor(load_experiment(write_experiment(csv_text="time_s,elongation_m\n" + rows + "\n")), CHANNELS)


def direct(predictor, x, effects):
    """The run with every effect inside the C++ pipeline, as before the shortcut."""
    return predictor.select(predictor.simulate(x, effects))


def test_an_instrument_at_the_same_coordinates_reads_the_last_run_bit_for_bit(write_experiment, runs):
    predictor = sealed(write_experiment)
    x = np.array([c.start for c in predictor.baseline.space])
    first = parse_effects(["sensor_offset:offset_Pa=3e3"])
    second = parse_effects(["load_cell:offset_N=-4"])
    for effects in (first, second, first):
        shortcut, full = predictor.predict(x, effects), direct(predictor, x, effects)
        assert all(np.array_equal(shortcut[c], full[c]) for c in CHANNELS)
    # One run of the model for three instrument predictions (plus the three direct ones).
    assert runs["runs"] == 1 + 3


def test_other_coordinates_or_a_physical_effect_run_the_model(write_experiment, runs):
    predictor = sealed(write_experiment)
    x = np.array([c.start for c in predictor.baseline.space])
    offset = parse_effects(["sensor_offset:offset_Pa=3e3"])
    predictor.predict(x, offset)
    moved = x.copy()
    moved[0] *= 1.01
    shortcut, full = predictor.predict(moved, offset), direct(predictor, moved, offset)
    assert all(np.array_equal(shortcut[c], full[c]) for c in CHANNELS)
    assert runs["runs"] == 2 + 1
    dead = parse_effects(["dead_volume:volume_fraction=0.05"])
    predictor.predict(moved, dead)
    predictor.predict(moved, dead)
    assert runs["runs"] == 3 + 2  # a dead volume changes the run itself: simulated every time


def test_a_transducer_that_drives_a_supplied_test_is_not_an_instrument_of_it(write_experiment):
    toml = write_experiment(
        csv_text="time_s,elongation_m,pressure_kPa\n0,0,200\n1,0,300\n2,0,400\n3,0,300\n4,0,200\n",
        toml_test_extra='gas = "supplied"',
    )
    predictor = Predictor(load_experiment(toml), ["force_N"])
    (pressure,) = parse_effects(["sensor_offset:offset_Pa=3e3"])
    (force,) = parse_effects(["load_cell:offset_N=-4"])
    assert not predictor.reads_the_model(pressure)  # it changes the pressure that drives the model
    assert predictor.reads_the_model(force)
    x = np.array([c.start for c in predictor.baseline.space])
    for effects in ([pressure], [force]):
        assert np.array_equal(predictor.predict(x, effects)["force_N"], direct(predictor, x, effects)["force_N"])


def test_a_play_shorter_than_a_sample_moves_the_muscle_as_on_a_fine_record(write_experiment):
    # Two stretch cycles of 25 mm, 2.5 mm of travel between samples, a play of 1 mm: the muscle
    # stands still for the first 40 % of the interval after each turn, then moves at the
    # crosshead's rate, and the friction follows that rate. The truth is the same run on a record
    # 64 times finer; the Predictor's run with the play is read at the samples.
    up = [0.0025 * k for k in range(11)]
    elongation = np.array([0.0] * 12 + up + up[-2::-1] + up[1:] + up[-2::-1] + [0.0] * 12)
    time = 0.5 * np.arange(elongation.size)
    rows = "\n".join(f"{t:.1f},{e:.4f}" for t, e in zip(time, elongation))
    predictor = Predictor(load_experiment(write_experiment(csv_text="time_s,elongation_m\n" + rows + "\n")), CHANNELS)
    x = np.array([c.start for c in predictor.baseline.space])
    play = parse_effects(["fixture_slack:slack_m=0.001"])
    params, pressure = predictor.baseline.model_params(x)
    initial = predictor.initial_state(params, pressure)
    fine_time = np.linspace(time[0], time[-1], 64 * (time.size - 1) + 1)
    fine = pamkit.simulate_measurement(
        params, initial, pamkit.ElongationTrajectory(fine_time, np.interp(fine_time, time, elongation)), play
    )
    truth = np.asarray(fine.force_N)[::64]
    on_samples = pamkit.simulate_measurement(params, initial, predictor.trajectory, play)
    error_on_samples = np.abs(np.asarray(on_samples.force_N) - truth).max()
    error = np.abs(predictor.predict(x, play)["force_N"] - truth).max()
    # Measured: 3.2 N on the samples' straight lines (the muscle moving through the whole interval
    # after each turn, at 60 % of the crosshead's rate), 1e-12 N on eight knots an interval.
    assert error_on_samples > 2.0
    assert error < 0.01 * error_on_samples
