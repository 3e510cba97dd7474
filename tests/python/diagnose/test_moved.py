"""The channels an effect on the physics moves in a test (candidates.note_moved_channels), found by
its fit against the model without it: checked against what the model's equations let each effect
reach on a sealed muscle stretched by a tensile machine."""

from types import SimpleNamespace

import numpy as np

from pamkit.diagnosis.series.calibrate import fit_baseline, one_blas_thread
from pamkit.diagnosis.series.candidates import MOVES_CHANNEL, candidates, fit_candidate, note_moved_channels
from pamkit.diagnosis.series.kinds import build_problem
from pamkit.effects import catalog
from pamkit.io.experiment import load_experiment
from pamkit.synth.dataset import synthesize


def test_each_physical_effect_moves_the_channels_its_equations_reach(tmp_path):
    # bench_diagnose's seed 1001, a viscoelastic bladder hidden. The crosshead sets the length, and
    # the braid alone sets the gas's volume from it: the bladder's stress moves the force and
    # neither the gas's pressure nor its temperature; a heat exchange with the wall moves the gas's
    # temperature, so its pressure and the force.
    expected = {
        "bladder_viscoelasticity": ["force_N"],
        "heat_transfer": ["force_N", "gauge_pressure_Pa", "temperature_K"],
    }
    with one_blas_thread():
        problem = build_problem(load_experiment(synthesize("bladder_viscoelasticity", 1001, tmp_path).experiment))
        baseline = fit_baseline(problem)
        factories = dict(candidates(catalog(), problem))
        for name in expected:
            fitted = fit_candidate(problem, baseline, factories[name], name)
            assert fitted.error is None, name
    for name, channels in expected.items():
        assert problem.moved_channels[name] == channels, name
    assert set(problem.moved_channels) == set(expected)  # an instrument names its own channels


def fake_problem(predict):
    """Two channels of unit noise, the model without the effect given by `predict`."""
    return SimpleNamespace(
        channels=["force_N", "gauge_pressure_Pa"],
        sigma={"force_N": 1.0, "gauge_pressure_Pa": 1.0},
        predictor=SimpleNamespace(predict=lambda base_x, effects: predict()),
        moved_channels={},
    )


def test_a_channel_moves_beyond_a_thousandth_of_its_noise_and_a_failed_run_notes_nothing():
    physical = SimpleNamespace(channels_changed=lambda: [], name=lambda: "bladder_viscoelasticity")
    with_it = {"force_N": np.array([0.0, 2.0]), "gauge_pressure_Pa": np.array([0.0, 0.5 * MOVES_CHANNEL])}
    problem = fake_problem(lambda: {"force_N": np.zeros(2), "gauge_pressure_Pa": np.zeros(2)})
    note_moved_channels(problem, physical, np.zeros(0), with_it)
    assert problem.moved_channels == {"bladder_viscoelasticity": ["force_N"]}

    def fails():
        raise RuntimeError("the model cannot run there")

    problem = fake_problem(fails)
    note_moved_channels(problem, physical, np.zeros(0), with_it)  # the fit stands, nothing is known
    assert problem.moved_channels == {}
