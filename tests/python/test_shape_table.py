"""The shape table through the bindings (ShapeTable, simulate_measurement's `shapes`) and in the
diagnosis's Predictor: read where it applies, with the same channels bit for bit, ignored where
it does not (tests/cpp/shape_table.test.cpp and tests/cpp/effects/shape_table.test.cpp check the
C++ side)."""

import numpy as np
import pytest

import pamkit._core as core
from pamkit.diagnosis.series.model import Predictor
from pamkit.io.experiment import load_experiment
from pamkit.synth.dataset import synthesize

CHANNELS = ("time_s", "elongation_m", "force_N", "gauge_pressure_Pa", "temperature_K")
INITIAL = core.InitialState(length_m=0.167, gauge_pressure_Pa=236.63e3)  # table C.2, 90 %


def heat_and_friction() -> core.MuscleParams:
    """PAM 2 with the thesis's friction (table C.4) and a gas that exchanges heat in 2 s."""
    params = core.MuscleParams()
    gas = params.gas
    gas.process = core.GasProcess.heat_transfer
    gas.heat_transfer_time_constant_s = 2.0
    params.gas = gas
    return params


def same_bits(a: core.Measurement, b: core.Measurement) -> bool:
    return all(np.asarray(getattr(a, c)).tobytes() == np.asarray(getattr(b, c)).tobytes() for c in CHANNELS)


def test_table_holds_the_closure_shapes():
    crosshead = core.thesis_protocol(0.04, 2.5e-3, 1)
    table = core.ShapeTable(core.MuscleBuild(), INITIAL.length_m, crosshead)
    assert len(table) == len(crosshead)
    np.testing.assert_array_equal(table.length_m, INITIAL.length_m + np.asarray(crosshead.elongation_m))
    geometry = core.BraidGeometry(core.MuscleBuild())
    for k in (0, len(table) // 3, len(table) - 1):
        # Warm-started against a cold solve: Boost's Newton tolerance, 47 bits (~7e-15 relative).
        assert table.shape(k).diameter == pytest.approx(geometry.shape(table.length_m[k]).diameter, rel=1e-14, abs=0)
    with pytest.raises(IndexError, match="sample"):
        table.shape(len(table))
    with pytest.raises(ValueError, match="outside the braid's range"):
        core.ShapeTable(core.MuscleBuild(), INITIAL.length_m, core.ElongationTrajectory([0.0, 1.0], [0.0, 1.0]))


def test_sealed_run_reads_the_table_with_the_same_bits():
    params = heat_and_friction()
    crosshead = core.thesis_protocol(0.04, 2.5e-3, 2, 0.1, 1.0)
    table = core.ShapeTable(params, INITIAL.length_m, crosshead)
    assert table.applies_to(core.MuscleModel(params, INITIAL), crosshead)
    effects = [core.EffectCatalog.builtin().parse("dead_volume")]
    plain = core.simulate_measurement(params, INITIAL, crosshead, effects)
    tabulated = core.simulate_measurement(params, INITIAL, crosshead, effects, shapes=table)
    assert tabulated.statistics.tabulated_shapes == len(crosshead)
    assert plain.statistics.tabulated_shapes == 0
    assert same_bits(tabulated, plain)
    run = core.Simulator().run(core.MuscleModel(params, INITIAL), crosshead, shapes=table)
    assert run.statistics.tabulated_shapes == len(crosshead)


@pytest.mark.parametrize("spec", ["fixture_slack:slack_m=0.001", "fiber_compliance"])
def test_an_effect_that_moves_the_muscle_or_stretches_its_fibers_leaves_it_unread(spec):
    params = heat_and_friction()
    crosshead = core.thesis_protocol(0.04, 2.5e-3, 1)
    table = core.ShapeTable(params, INITIAL.length_m, crosshead)
    effects = [core.EffectCatalog.builtin().parse(spec)]
    plain = core.simulate_measurement(params, INITIAL, crosshead, effects)
    with_table = core.simulate_measurement(params, INITIAL, crosshead, effects, shapes=table)
    assert with_table.statistics.tabulated_shapes == 0
    assert same_bits(with_table, plain)


def test_predictor_reads_cached_tables_for_sealed_runs(tmp_path):
    experiment = load_experiment(synthesize("none", 1000, tmp_path).experiment)
    predictor = Predictor(experiment, ["force_N"])
    x = np.array([c.start for c in predictor.baseline.space])
    first = predictor.simulate(x, [])
    assert first.statistics.tabulated_shapes == len(predictor.trajectory)
    # Another friction scale keeps the build and the initial length: the same table, no new one.
    names = [c.name for c in predictor.baseline.space]
    x_friction = x.copy()
    x_friction[names.index("friction_scale")] *= 1.1
    predictor.simulate(x_friction, [])
    assert len(predictor._shape_tables) == 1
    # The run is the one without a table, bit for bit.
    params, pressure_Pa = predictor.baseline.model_params(x)
    initial = predictor.initial_state(params, pressure_Pa)
    plain = core.simulate_measurement(params, initial, predictor.trajectory, [], predictor.simulator)
    assert same_bits(first, plain)
    # A motion effect: no table is built or read.
    slack = core.EffectCatalog.builtin().parse("fixture_slack:slack_m=0.001")
    assert predictor.simulate(x, [slack]).statistics.tabulated_shapes == 0
    assert len(predictor._shape_tables) == 1
