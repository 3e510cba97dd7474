"""The decision rules of python/pamkit/diagnosis/series/decide.py on scores made by hand: what each rule
does with two candidates, without fitting anything."""

import sys
from types import SimpleNamespace

import numpy as np
import pytest
from conftest import SOURCE_DIR

from pamkit._core import EffectStage, GasMode, Resolution
from pamkit.diagnosis.coordinates import NO_COST_AT_BOUND, Finding
from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.causes import explains_more, placed, resolves, second_holds
from pamkit.diagnosis.series.decide import PAIR_TRIGGER, Judgement, decide, gain_over, judge, marginal
from pamkit.diagnosis.series.findings import moves_against, sub_sample_play, unresolved, within_resolution
from pamkit.diagnosis.series.instruments import (
    MISREAD_GAIN,
    STANDS_OUT,
    STRUCTURE_LEFT,
    holds_vacuum,
    misread,
    noise_ratios,
    reads_left,
    uncredited,
    unfounded,
)
from pamkit.diagnosis.series.score import Score, credited_channels
from pamkit.diagnosis.significance import MIN_GAIN, NONE_WITHIN_NOISE
from pamkit.effects import catalog
from pamkit.io.experiment import load_experiment

sys.path.insert(0, str(SOURCE_DIR / "tests"))  # tests/independent: a folder, not an installed package
from independent.dmsp import DmspTruth, write_dmsp_cyclic  # noqa: E402

SAMPLES = 1000
rng = np.random.default_rng(7)
SHARED = rng.normal(0.0, 0.02, SAMPLES)  # what the bootstrap draws do to every candidate alike
ROWS = 20


def problem(channels=("force_N",), measured=None):
    """Channels measured as zeros (or `measured`), each with unit noise, every row held out."""
    measured = measured or {c: np.zeros(ROWS) for c in channels}
    return SimpleNamespace(
        channels=list(channels),
        measured=measured,
        sigma={c: 1.0 for c in channels},
        held_mask=np.ones(ROWS, bool),
        experiment=SimpleNamespace(gas=GasMode.sealed),
        moved_channels={},
    )


def effect(name: str, channels=(), stage=EffectStage.physics):
    return SimpleNamespace(
        name=lambda: name,
        channels_changed=lambda: list(channels),
        stage=lambda: stage,
        reads_supplied_pressure=lambda: False,
        parameters=lambda: [],
    )


def fit(name, predicted, effects=None):
    effects = [effect(name)] if effects is None else effects
    return Fit(name, effects, np.zeros(0), {}, predicted, {c: 0.0 for c in predicted}, 1)


def candidate(name: str, gain: float, samples: np.ndarray, objections=(), channels=("force_N",)) -> Judgement:
    score = Score(
        rmse={c: 1.0 for c in channels},
        gain={c: gain for c in channels},
        gain_ci95={c: [gain - 0.04, gain + 0.04] for c in channels},
        combined_gain=gain,
        combined_ci95=[float(np.percentile(samples, 2.5)), float(np.percentile(samples, 97.5))],
        delta_bic=-100.0,
        credited_gain=gain,
        credited_ci95=[gain - 0.04, gain + 0.04],
        combined_samples=samples,
    )
    return Judgement(fit(name, {c: np.zeros(ROWS) for c in channels}), score, True, [], list(objections))


BASELINE = fit("none", {"force_N": np.full(ROWS, 5.0)}, effects=[])  # 5 noise sigmas off everywhere


def test_two_mechanisms_the_data_cannot_tell_apart_are_not_a_cause():
    # Gains 0.30 and 0.29 on the same draws, each draw's difference spread 0.03: the paired
    # interval of the difference holds zero.
    best = candidate("dead_volume", 0.30, 0.30 + SHARED + rng.normal(0, 0.02, SAMPLES))
    rival = candidate("fiber_compliance", 0.29, 0.29 + SHARED + rng.normal(0, 0.02, SAMPLES))
    decision = decide(problem(), BASELINE, [best, rival])
    assert decision.cause == "unexplained" and decision.causes == []
    assert decision.rejected is best and "fiber_compliance explains the held-out units as well" in best.reasons()[0]
    assert decision.margins["over_rival"] <= 0.0


def test_a_cause_that_beats_its_rival_on_the_same_draws_is_named():
    # The same spread, 0.10 apart: the difference's interval lies above zero.
    best = candidate("dead_volume", 0.40, 0.40 + SHARED + rng.normal(0, 0.02, SAMPLES))
    rival = candidate("fiber_compliance", 0.30, 0.30 + SHARED + rng.normal(0, 0.02, SAMPLES))
    decision = decide(problem(), BASELINE, [best, rival])
    assert decision.cause == "dead_volume" and decision.margins["over_rival"] > 0.0
    assert [c.label for c in decision.causes] == ["dead_volume"] and decision.named is best


def test_a_cause_ahead_of_its_rival_by_less_than_a_cause_explains_is_named_with_it_close_behind():
    # 0.611 against 0.607 on the same draws, each draw's difference 0.004 +- 0.0005: the paired
    # interval lies above zero, and the first is named (rule 6); over the second it explains
    # 0.004 / 0.393 = 1 % of what that leaves, where a cause explains MIN_GAIN (3 %): the second is
    # its close rival, for which the report names a test that would confirm the first. 0.10
    # ahead (rule 1's share many times over), it has none.
    for rival_gain, close in ((0.607, True), (0.511, False)):
        best = candidate("fiber_compliance", 0.611, 0.611 + SHARED + rng.normal(0, 0.0005, SAMPLES))
        rival = candidate("dead_volume", rival_gain, rival_gain + SHARED)
        decision = decide(problem(), BASELINE, [best, rival])
        assert decision.cause == "fiber_compliance" and decision.margins["over_rival"] > 0.0
        assert (best.close_rival is rival) is close
        assert gain_over(best, rival) == pytest.approx((0.611 - rival_gain) / (1.0 - rival_gain))


def test_a_rival_that_is_not_credible_does_not_block_a_cause():
    best = candidate("dead_volume", 0.30, 0.30 + SHARED + rng.normal(0, 0.02, SAMPLES))
    rival = candidate("sensor_offset", 0.29, 0.29 + SHARED, objections=["gain = 0.5 ended at its search bound"])
    decision = decide(problem(), BASELINE, [best, rival])
    assert decision.cause == "dead_volume" and "over_rival" not in decision.margins


def test_an_unneeded_instrument_that_ties_leaves_the_cause_untold():
    # A load cell refused only because the force was within the noise before it is no cause, but
    # as good a reading as the viscoelastic bladder it ties with: neither is named. Beaten on the
    # same draws, it does not stand in the cause's way.
    for rival_gain, named in ((0.29, False), (0.20, True)):
        best = candidate("bladder_viscoelasticity", 0.30, 0.30 + SHARED + rng.normal(0, 0.02, SAMPLES))
        rival = candidate("load_cell", rival_gain, rival_gain + SHARED + rng.normal(0, 0.02, SAMPLES))
        rival.unneeded = ["force_N was within the noise before it"]
        decision = decide(problem(), BASELINE, [best, rival])
        assert (decision.cause == "bladder_viscoelasticity") is named
        assert (decision.cause == "unexplained") is not named


def test_a_part_of_what_a_better_fit_explains_is_not_named():
    # A candidate that cannot be named (a parameter at its bound) explains the same channel 0.15
    # better on the same draws: the credible one behind it may be fitting a piece of that.
    better = candidate("load_cell", 0.45, 0.45 + SHARED, objections=["nonlinearity_per_kN = 0.5 at its bound"])
    lesser = candidate("bladder_viscoelasticity", 0.30, 0.30 + SHARED + rng.normal(0, 0.02, SAMPLES))
    decision = decide(problem(), BASELINE, [better, lesser])
    assert decision.cause == "unexplained" and decision.causes == []
    assert any("load_cell explains the held-out units significantly better" in r for r in lesser.reasons())


def test_a_better_fit_that_explains_no_more_does_not_make_a_cause_a_part_of_it():
    # In a supplied test a load cell lagging 1.5 s (implausible) and the transducer lagging 1.5 s
    # draw the same force: 0.899 against 0.898, better on the same draws by less than a cause's
    # worth of what the credible one leaves (gain_over below MIN_GAIN). It explains the same thing,
    # not more of it: the transducer's lag is named. Better by a cause's worth, it is not.
    for better_gain, named in ((0.899, True), (0.898 + 1.1 * MIN_GAIN * (1 - 0.898), False)):
        better = candidate("sensor_lag", better_gain, better_gain + SHARED)
        better.findings = [Finding("time_constant_s", 1.5, None, [0.0, 0.1], "test")]
        lesser = candidate("sensor_lag", 0.898, 0.898 + SHARED)
        assert np.all(better.score.combined_samples > lesser.score.combined_samples)
        decision = decide(problem(), BASELINE, [better, lesser])
        assert (decision.causes != [] and decision.causes[0].judgement is lesser) is named
    # Refused for what it explains (an instrument not needed), the better one says the structure
    # may be the base model's: the lesser is a piece of it. Its values only narrowly out, it is as
    # good a reading: the two are untold apart.
    for refusal, words in (("unneeded", "may be a part of what it fits"), ("near", "do not tell the two apart")):
        better = candidate("sensor_offset", 0.899, 0.899 + SHARED)
        if refusal == "unneeded":
            better.unneeded = ["gauge_pressure_Pa was within the noise before it"]
        else:
            better.findings = [Finding("offset_Pa", 16e3, None, [-15e3, 15e3], "test")]
        lesser = candidate("load_cell", 0.898, 0.898 + SHARED)
        assert decide(problem(), BASELINE, [better, lesser]).causes == []
        assert any(words in r for r in lesser.reasons()), refusal


def test_one_delay_read_on_another_instrument_is_named_where_it_is_plausible():
    # In a supplied test a hose lagging the pressure by 0.40 s and a load cell lagging the force by
    # 0.40 s draw the same force (bench_near_model, supplied_sensor_lag at medium strength, seed 14:
    # 0.768 against 0.750, better on the same draws by more than a cause's worth of what the hose's
    # lag leaves). Each time constant inside the other's interval, they are one delay, which no load
    # cell has: the hose's lag is named. At another time constant the better fit is another
    # mechanism, and the lesser may be a piece of it.
    for load_cell_tau, named in ((0.401, True), (0.6, False)):
        better = candidate("sensor_lag:channel=force_N", 0.768, 0.768 + SHARED)
        better.fit.effects = [effect("sensor_lag")]
        better.fit.params = {"time_constant_s": load_cell_tau, "channel": "force_N"}
        better.fit.intervals = {"time_constant_s": (load_cell_tau - 0.007, load_cell_tau + 0.007)}
        better.findings = [Finding("time_constant_s", load_cell_tau, None, [0.0, 0.1], "test")]
        lesser = candidate("sensor_lag:channel=gauge_pressure_Pa", 0.750, 0.750 + SHARED)
        lesser.fit.effects = [effect("sensor_lag")]
        lesser.fit.params = {"time_constant_s": 0.3986, "channel": "gauge_pressure_Pa"}
        lesser.fit.intervals = {"time_constant_s": (0.3866, 0.4111)}
        assert gain_over(better, lesser) > MIN_GAIN
        decision = decide(problem(), BASELINE, [better, lesser])
        assert (decision.causes != [] and decision.causes[0].judgement is lesser) is named
        assert decision.rejected is better


def test_a_cause_stands_beside_a_better_fit_that_explains_another_channel():
    # The better candidate that cannot be named explains the pressure only; the credible one the
    # force: they explain different things, and the credible one is a cause.
    channels = ("force_N", "gauge_pressure_Pa")
    better = candidate("sensor_offset", 0.45, 0.45 + SHARED, objections=["at its bound"], channels=channels)
    better.score.gain["force_N"], better.score.gain_ci95["force_N"] = 0.0, [-0.01, 0.01]
    lesser = candidate("load_cell", 0.30, 0.30 + SHARED + rng.normal(0, 0.02, SAMPLES), channels=channels)
    lesser.score.gain["gauge_pressure_Pa"], lesser.score.gain_ci95["gauge_pressure_Pa"] = 0.0, [-0.01, 0.01]
    baseline = fit("none", {c: np.full(ROWS, 5.0) for c in channels}, effects=[])
    decision = decide(problem(channels), baseline, [better, lesser])
    assert decision.cause == "load_cell" and decision.rejected is better


def test_none_only_within_the_noise():
    # No significant candidate: `none` while every channel's held-out RMSE is within
    # NONE_WITHIN_NOISE of its noise, `unexplained` beyond it (the rule's factor, diagnosis/significance.py).
    weak = candidate("leak", 0.01, 0.01 + SHARED)
    weak.significant = False
    inside = fit("none", {"force_N": np.full(ROWS, 0.99 * NONE_WITHIN_NOISE)}, effects=[])
    outside = fit("none", {"force_N": np.full(ROWS, 1.01 * NONE_WITHIN_NOISE)}, effects=[])
    assert decide(problem(), inside, [weak]).cause == "none"
    assert decide(problem(), outside, [weak]).cause == "unexplained"


def instrument_case(own_before: float, other_after: float, instrument: str = "load_cell"):
    """An instrument effect on one coupled channel (a load cell on the force, or the sealed gas's
    pressure transducer): the baseline leaves its channel `own_before` and the other 5 noise sigmas
    off; the instrument's fit leaves its channel at the noise and the other at `other_after`."""
    channels = ("force_N", "gauge_pressure_Pa")
    own, other = ("force_N", "gauge_pressure_Pa") if instrument == "load_cell" else ("gauge_pressure_Pa", "force_N")
    p = problem(channels)
    baseline = fit("none", {other: np.full(ROWS, 5.0), own: np.full(ROWS, own_before)}, [])
    reader = effect(instrument, [own], EffectStage.measurement)
    corrected = fit(instrument, {other: np.full(ROWS, other_after), own: np.ones(ROWS)}, [reader])
    score = Score(
        rmse={other: other_after, own: 1.0},
        gain={other: 0.0, own: 0.5},
        gain_ci95={other: [0, 0], own: [0.4, 0.6]},
        combined_gain=0.3,
        combined_ci95=[0.2, 0.4],
        delta_bic=-100.0,
        credited_gain=0.5,
        credited_ci95=[0.4, 0.6],
    )
    return uncredited(p, corrected, score, baseline), noise_ratios(p, baseline)


def test_an_instrument_that_stands_out_from_the_base_models_misfit_is_credited():
    # The force STANDS_OUT times further off than the pressure the load cell cannot change.
    reasons, ratios = instrument_case(own_before=2.2 * STANDS_OUT * 3.0, other_after=3.0)
    assert ratios["force_N"] == pytest.approx(2.2 * STANDS_OUT * 3.0)
    assert reasons == []


def test_an_instrument_that_does_not_stand_out_may_be_the_base_models_misfit():
    reasons, _ = instrument_case(own_before=0.9 * STANDS_OUT * 3.0, other_after=3.0)
    assert len(reasons) == 1 and "does not stand out" in reasons[0]


def test_structure_within_the_noise_beside_an_instrument_is_no_objection():
    # The channel it cannot change ends within STRUCTURE_LEFT: nothing to compare it with.
    for instrument in ("load_cell", "sensor_offset"):
        reasons, _ = instrument_case(own_before=2.5, other_after=0.9 * STRUCTURE_LEFT, instrument=instrument)
        assert reasons == [], instrument


def force_case(on_force, own_after: float, other_after: float = 1.6, own_before: float = 2.9, gain: float = 0.1):
    """An effect on the force of a sealed test (`on_force`: a viscoelastic bladder, which moves the
    force and not the gas, or a load cell): the baseline leaves the force `own_before` and the
    pressure 1.6 noise sigmas off; the fit leaves the force `own_after` and the pressure
    `other_after`, gaining `gain` on the force and -0.1 on the pressure."""
    p = problem(("force_N", "gauge_pressure_Pa"))
    p.moved_channels["bladder_viscoelasticity"] = ["force_N"]
    baseline = fit("none", {"force_N": np.full(ROWS, own_before), "gauge_pressure_Pa": np.full(ROWS, 1.6)}, [])
    after = {"force_N": np.full(ROWS, own_after), "gauge_pressure_Pa": np.full(ROWS, other_after)}
    score = Score(
        rmse={"force_N": own_after, "gauge_pressure_Pa": other_after},
        gain={"force_N": gain, "gauge_pressure_Pa": -0.1},
        gain_ci95={"force_N": [gain - 0.05, gain + 0.05], "gauge_pressure_Pa": [-0.15, -0.05]},
        combined_gain=gain / 2,
        combined_ci95=[0.01, gain],
        delta_bic=-100.0,
        credited_gain=gain,
        credited_ci95=[gain - 0.05, gain + 0.05],
    )
    return uncredited(p, fit(on_force.name(), after, [on_force]), score, baseline)


def physical_case(own_after: float, other_after: float = 1.6, own_before: float = 2.9):
    return force_case(effect("bladder_viscoelasticity"), own_after, other_after, own_before)


def test_a_physical_effect_is_credited_on_the_channels_its_fit_moves():
    # An effect on the physics names no channel of its own: the channels it changes are those its
    # fit was seen to move in this test (candidates.note_moved_channels), all of them before a fit.
    p = problem(("force_N", "gauge_pressure_Pa", "temperature_K"))
    bladder = fit("bladder_viscoelasticity", {}, [effect("bladder_viscoelasticity")])
    assert credited_channels(p, bladder) == ["force_N", "gauge_pressure_Pa", "temperature_K"]
    p.moved_channels["bladder_viscoelasticity"] = ["force_N"]
    assert credited_channels(p, bladder) == ["force_N"]
    offset = fit("sensor_offset", {}, [effect("sensor_offset", ["gauge_pressure_Pa"], EffectStage.measurement)])
    assert credited_channels(p, offset) == ["gauge_pressure_Pa"]


def test_a_physical_effect_stands_out_by_leaving_its_own_channel_whole():
    # The force from 2.9x to 0.9x its noise beside a pressure left at 1.6x (bench_diagnose --mismatch
    # seed 3001's viscoelastic bladder): its model moved the force whole. Leaving the force at 2x,
    # less than STANDS_OUT times as far out as the pressure stays, it may be the base model's misfit
    # (another team's muscle declared 2 mm short: such a bladder gained 0.09 on the force and 0.22 on
    # the pressure it cannot move). An instrument that reads the force is not let off so.
    assert physical_case(own_after=0.9) == []
    assert physical_case(own_after=0.99 * STRUCTURE_LEFT) == []
    reasons = physical_case(own_after=2.0)
    assert len(reasons) == 1 and "does not stand out from what the base model leaves on gauge_pressure_Pa" in reasons[0]
    assert physical_case(own_after=2.0, own_before=1.01 * STANDS_OUT * 1.6) == []
    reasons, _ = instrument_case(own_before=2.9, other_after=1.6)
    assert any("does not stand out" in r for r in reasons)


def test_only_an_instruments_correction_is_refused_for_making_another_channel_worse():
    # A physical effect's baseline refitted beside it trades the channels as the model does; an
    # instrument's correction that makes another channel worse is a general corrector.
    assert physical_case(own_after=0.9, other_after=1.6) == []
    load_cell = effect("load_cell", ["force_N"], EffectStage.measurement)
    reasons = force_case(load_cell, own_after=1.0, other_after=1.1, gain=0.5)
    assert reasons == ["it makes gauge_pressure_Pa worse (held-out gain -0.10)"]


def test_the_inflation_transducer_needs_the_force_explained_however_far_out_its_pressure():
    # The sealed gas's pressure transducer read the declared inflation pressure: its offset and gain
    # trade against the calibrated inflation pressure, and its error shows as a pressure at odds with
    # a force the model explains. With the force left structured, even a pressure far further off
    # is refused; a load cell in the same place stands out.
    reasons, _ = instrument_case(own_before=10 * STANDS_OUT * 1.6, other_after=1.6, instrument="sensor_offset")
    assert len(reasons) == 1 and "does not stand out" in reasons[0]
    assert instrument_case(own_before=10 * STANDS_OUT * 1.6, other_after=1.6)[0] == []


def test_an_instrument_that_reads_off_must_leave_its_channel_unstructured_with_the_causes():
    # An error of what an instrument reads corrects that channel whole: with the causes named, a
    # load cell whose force is still beyond STRUCTURE_LEFT explains only a share of another misfit.
    # A time shift is not held to it (a skew beside a leak's drift on the same channel).
    p = problem(("force_N", "gauge_pressure_Pa"))
    load_cell = effect("load_cell", ["force_N"], EffectStage.measurement)
    shift = effect("time_skew", ["force_N"], EffectStage.measurement)
    shift.parameters = lambda: [SimpleNamespace(resolution=Resolution.sample_interval)]
    for force, founded in ((0.95 * STRUCTURE_LEFT, True), (1.05 * STRUCTURE_LEFT, False)):
        final = fit("load_cell", {"force_N": np.full(ROWS, force), "gauge_pressure_Pa": np.zeros(ROWS)}, [load_cell])
        assert (reads_left(p, final, [load_cell]) == []) is founded
        assert reads_left(p, final, [shift]) == []


def test_a_shift_below_one_sample_outdoes_no_cause():
    # A skew of less than a sample (the sampling's own artefact: two clocks interpolated) that
    # explains the channel better is no mechanism the credible candidate could be a piece of.
    better = candidate("time_skew", 0.45, 0.45 + SHARED)
    better.below_resolution = ["offset_s = 0.005 is below the sample interval (0.02)"]
    lesser = candidate("dead_volume", 0.30, 0.30 + SHARED + rng.normal(0, 0.02, SAMPLES))
    decision = decide(problem(), BASELINE, [better, lesser])
    assert decision.cause == "dead_volume" and decision.rejected is better


def test_a_play_shorter_than_a_sample_is_named_only_where_no_sub_sample_shift_explains_as_much():
    # A crosshead moving 1 mm between samples, a play fitted at 0.5 mm: the samples just after
    # each turn carry it, as they carry a channel shifted by less than one sample. A shift that
    # explains the held-out units as well (the same draws) leaves the play untold from the
    # sampling's artefact; one it beats on the same draws, or a play longer than one sample's
    # travel, does not.
    p = problem()
    p.experiment.elongation_m = 1e-3 * np.arange(ROWS)

    def play(slack_m, gain):
        j = candidate("fixture_slack", gain, gain + SHARED + rng.normal(0, 0.01, SAMPLES))
        slack = effect("fixture_slack", ["force_N"], EffectStage.motion)
        slack.parameters = lambda: [SimpleNamespace(name="slack_m", resolution=Resolution.travel_per_sample)]
        j.fit.effects, j.fit.params = [slack], {"slack_m": slack_m}
        return j

    def shift(gain):
        j = candidate("time_skew", gain, gain + SHARED + rng.normal(0, 0.01, SAMPLES))
        skew = effect("time_skew", ["force_N"], EffectStage.measurement)
        skew.parameters = lambda: [SimpleNamespace(name="offset_s", resolution=Resolution.sample_interval)]
        j.fit.effects = [skew]
        j.below_resolution = ["offset_s = 0.005 is below the sample interval (0.02)"]
        return j

    for slack_m, shift_gain, named in ((0.5e-3, 0.30, False), (0.5e-3, 0.10, True), (1.5e-3, 0.30, True)):
        lead, rival = play(slack_m, 0.30), shift(shift_gain)
        decision = decide(p, BASELINE, [rival, lead] if shift_gain >= 0.30 else [lead, rival])
        assert (decision.cause == "fixture_slack") is named, (slack_m, shift_gain, decision.cause)
        if not named:
            assert "a shift below one sample, explains the held-out units as well" in lead.reasons()[0]
    # The resolution: a sealed run follows eight knots an interval after each turn, so a play of
    # half a sample's travel is resolved; a supplied test, evaluated at its samples, does not.
    assert unresolved(p, play(0.5e-3, 0.30).fit) == []
    assert unresolved(p, play(0.1e-3, 0.30).fit) == [
        "slack_m = 0.0001 is below the travel between the knots its runs follow (8 between samples) (0.000125)"
    ]
    p.experiment.gas = GasMode.supplied
    assert unresolved(p, play(0.5e-3, 0.30).fit) == [
        "slack_m = 0.0005 is below the crosshead's travel between samples (0.001)"
    ]
    p.experiment.gas = GasMode.sealed
    # In a pair the play's parameter carries its effect's name.
    pair = play(0.5e-3, 0.30)
    pair.fit.effects.append(effect("load_cell", ["force_N"], EffectStage.measurement))
    pair.fit.params = {"fixture_slack.slack_m": 0.5e-3}
    assert sub_sample_play(p, pair.fit)
    pair.fit.params = {"fixture_slack.slack_m": 1.5e-3}
    assert not sub_sample_play(p, pair.fit)


def test_a_play_that_makes_a_channel_it_moves_worse_is_no_play():
    # A fixture's play moves the muscle, whose length drives the force and the gas alike: fitted to
    # a pressure logged late, it improves the pressure and makes the force worse (bench_families
    # subsample_skew seed 10: force -0.33, pressure 0.53); every play named right on the near-model
    # bench's seeds 1-30 gained on both (force 0.02-0.90). An effect on the physics may trade the
    # channels beside a baseline refitted with it (a heat exchange beside a transducer's offset).
    channels = ("force_N", "gauge_pressure_Pa")
    p = problem(channels)
    p.moved_channels = {"fixture_slack": list(channels), "heat_transfer": list(channels)}

    def judged(name, stage, force_gain, force_ci95):
        j = candidate(name, 0.3, 0.3 + SHARED, channels=channels)
        j.fit.effects = [effect(name, (), stage)]
        j.score.gain = {"force_N": force_gain, "gauge_pressure_Pa": 0.53}
        j.score.gain_ci95 = {"force_N": force_ci95, "gauge_pressure_Pa": [0.49, 0.57]}
        return j

    reasons = moves_against(p, judged("fixture_slack", EffectStage.motion, -0.33, [-0.39, -0.30]))
    assert reasons == [
        "it makes force_N worse (gain -0.33) for gauge_pressure_Pa (gain 0.53): the muscle's motion moves "
        "every channel it drives alike, so what it explains is one channel's timing, not the muscle's"
    ]
    slack = judged("fixture_slack", EffectStage.motion, -0.33, [-0.39, -0.30])
    baseline = fit("none", {c: np.full(ROWS, 5.0) for c in channels}, effects=[])
    decision = decide(p, baseline, [slack])
    assert decision.cause == "unexplained" and decision.rejected is slack
    # a weak play's force gain within its noise, either side of zero, is no objection
    assert moves_against(p, judged("fixture_slack", EffectStage.motion, 0.02, [-0.01, 0.05])) == []
    assert moves_against(p, judged("fixture_slack", EffectStage.motion, -0.01, [-0.03, 0.01])) == []
    assert moves_against(p, judged("heat_transfer", EffectStage.physics, -0.33, [-0.39, -0.30])) == []


def test_a_shift_at_one_sample_is_a_rival_not_an_artefact():
    # A lag fitted at 0.044 s for a 0.05 s sample interval, its 95 % interval reaching past the
    # 0.045 s the sampling resolves: the data do not place it below. Better on the same draws, it
    # leaves the candidate behind it a possible piece of it; as good, a tie. Either way the
    # candidate is not named (near-model bench: a one-sample lag was named a skew of 0.0508 s).
    for gain in (0.45, 0.30):
        near = candidate("sensor_lag", gain, gain + SHARED)
        near.below_resolution = ["time_constant_s = 0.044 is below 0.9 of the sample interval (0.045)"]
        near.near_resolution = True
        lesser = candidate("time_skew", 0.30, 0.30 + SHARED + rng.normal(0, 0.02, SAMPLES))
        decision = decide(problem(), BASELINE, [near, lesser] if gain > 0.30 else [lesser, near])
        assert decision.causes == [] and decision.cause == "unexplained"


def test_an_instruments_error_beside_a_first_cause_needs_its_channel_off():
    # The sealed gas's pressure transducer, first cause or second, is founded only where the model
    # without it leaves its channel beyond NONE_WITHIN_NOISE; one that edits the model (a dead
    # volume) is not held to it, nor a load cell (held to its gain on the force instead: misread).
    channels = ("force_N", "gauge_pressure_Pa")
    p = problem(channels)
    sensor = effect("sensor_offset", ["gauge_pressure_Pa"], EffectStage.measurement)
    volume = effect("dead_volume", ["gauge_pressure_Pa"], EffectStage.physics)
    load_cell = effect("load_cell", ["force_N"], EffectStage.measurement)
    for pressure, founded in ((0.95 * NONE_WITHIN_NOISE, False), (1.05 * NONE_WITHIN_NOISE, True)):
        first = fit("leak", {"force_N": np.full(ROWS, 1.0), "gauge_pressure_Pa": np.full(ROWS, pressure)}, [])
        assert (unfounded(p, first, [sensor]) == []) is founded
        assert unfounded(p, first, [volume]) == []
        assert unfounded(p, first, [load_cell]) == []


def test_a_strained_inflation_pressure_founds_a_transducers_error():
    # The calibrated inflation pressure at the end of its search (the declared value within the
    # transducer's 5 %): the data start at another pressure than the file declares, and a pressure
    # transducer's error is founded even with its channel within the noise.
    p = problem(("force_N", "gauge_pressure_Pa"))
    sensor = effect("sensor_offset", ["gauge_pressure_Pa"], EffectStage.measurement)
    load_cell = effect("load_cell", ["force_N"], EffectStage.measurement)
    within = {"force_N": np.full(ROWS, 1.0), "gauge_pressure_Pa": np.full(ROWS, 1.5)}
    for side, founded in ((None, False), ("upper", True)):
        baseline = fit("none", within, [])
        baseline.coordinates = inflation_at_bound(side)
        assert (unfounded(p, baseline, [sensor]) == []) is founded
        assert unfounded(p, baseline, [load_cell]) == []  # the force's instrument is held to misread


def inflation_at_bound(side):
    """The sealed gas's calibrated inflation pressure as a coordinate, at `side` of its search."""
    coordinate = SimpleNamespace(
        value=lambda x: 1.05,
        at_bound=lambda x: side,
        implausible=lambda value: False,
        bound_value=lambda side: 1.05,
        plausible=(0.95, 1.05),
        source="the declared inflation pressure within the transducer's 5 %",
    )
    return {"inflation_gauge_pressure_Pa": (coordinate, 0.0)}


def test_a_transducers_correction_is_not_bound_by_the_pressure_it_read():
    # The declared inflation pressure was read on the pressure transducer: a fit that corrects that
    # transducer and ends with the inflation pressure at the end of its 5 % box is not refused for
    # it (the base model's strain, reported); a dead volume that does is.
    channels = ("force_N", "gauge_pressure_Pa")
    p = problem(channels)
    p.experiment.time_s = np.arange(ROWS, dtype=float)
    off = {"force_N": np.full(ROWS, 1.0), "gauge_pressure_Pa": np.full(ROWS, 5.0)}
    baseline = fit("none", off, [])
    score = Score(
        rmse={c: 1.0 for c in channels},
        gain={"force_N": 0.0, "gauge_pressure_Pa": 0.8},
        gain_ci95={"force_N": [-0.01, 0.01], "gauge_pressure_Pa": [0.7, 0.9]},
        combined_gain=0.5,
        combined_ci95=[0.4, 0.6],
        delta_bic=-100.0,
        credited_gain=0.8,
        credited_ci95=[0.7, 0.9],
    )
    for effect_, stage, refused in (
        ("sensor_offset", EffectStage.measurement, False),
        ("dead_volume", EffectStage.physics, True),
    ):
        candidate_fit = fit(
            effect_,
            {"force_N": np.ones(ROWS), "gauge_pressure_Pa": np.ones(ROWS)},
            [effect(effect_, ["gauge_pressure_Pa"], stage)],
        )
        candidate_fit.coordinates = inflation_at_bound("upper")
        j = judge(p, candidate_fit, score, baseline)
        assert any(f.parameter == "inflation_gauge_pressure_Pa" for f in j.findings) is refused
        assert any(f.parameter == "inflation_gauge_pressure_Pa" for f in j.strain) is not refused


def test_a_bound_that_costs_the_fit_nothing_is_told_apart_from_a_strain():
    # A wind resting on a flat floor at its tolerance's end (the bundled example: lifting the bound
    # lowers the RMSE by 5e-7) holds nothing back; one whose bound costs 3 % of the RMSE does.
    resting = Finding("fiber_revolutions", 2.1, 2.1, [1.9, 2.1], "[uncertain]", beyond=2.101, rmse_drop=5e-7)
    straining = Finding("fiber_revolutions", 2.1, 2.1, [1.9, 2.1], "[uncertain]", beyond=2.3, rmse_drop=0.03)
    implausible = Finding("friction_scale", 0.05, None, [0.1, 10.0], "its range")
    assert resting.costs_nothing and not straining.costs_nothing and not implausible.costs_nothing
    assert Finding("x", 1.0, 1.0, [0.0, 1.0], "s", beyond=1.0, rmse_drop=NO_COST_AT_BOUND).costs_nothing is False


def friction_scale_at(value: float):
    """The baseline's friction scale as a coordinate, found at `value` (plausible [0.1, 10], the
    search [0, 20])."""
    coordinate = SimpleNamespace(
        value=lambda x: value,
        at_bound=lambda x: None,
        implausible=lambda v: not 0.1 <= v <= 10.0,
        bound_value=lambda side: None,
        plausible=(0.1, 10.0),
        source="test",
    )
    return {"friction_scale": (coordinate, 0.0)}


def test_a_value_the_data_leave_free_to_be_plausible_is_not_held_against_a_cause():
    # A friction scale found at 0.05, below its plausible 0.1: with a 95 % interval of [0, 0.95]
    # (a test whose crosshead holds still) the data do not say it is implausible, and a cause
    # beside it may be named; with [0.04, 0.06] they do, and it is the base model's strain when the
    # calibrated baseline ended there too, the candidate's own finding when the candidate moved it
    # there.
    p = problem()
    p.experiment.time_s = np.arange(ROWS, dtype=float)
    off = {"force_N": np.full(ROWS, 5.0)}
    score = candidate("slack", 0.8, SHARED + 0.8).score
    for baseline_ends_there in (True, False):
        baseline = fit("none", off, [])
        baseline.coordinates = friction_scale_at(0.05 if baseline_ends_there else 1.0)
        for interval, free in (((0.0, 0.95), True), ((0.04, 0.06), False)):
            cause = fit("slack", {"force_N": np.ones(ROWS)})
            cause.coordinates = friction_scale_at(0.05)
            cause.intervals = {"friction_scale": interval}
            j = judge(p, cause, score, baseline)
            held = [f.parameter for f in j.findings]
            strained = [f.parameter for f in j.strain]
            if free:
                assert held == [] and strained == [] and j.credible
            elif baseline_ends_there:
                assert held == [] and strained == ["friction_scale"] and j.credible
            else:
                assert held == ["friction_scale"] and not j.credible


def test_a_bound_the_candidate_left_at_no_cost_is_not_held_against_it():
    # A supplied test's hose lag draws the loop the braid's friction drew, and the joint fit takes
    # the friction scale to its search bound 0 (bench_near_model, supplied_sensor_lag at strength
    # strong, seed 6): lifting the bound would lower the fitted RMSE by 8.5e-6 of itself, below
    # NO_COST_AT_BOUND, and its interval [0, 1.19] reaches its plausible [0.1, 10], so the bound
    # holds nothing back and the lag is credible, the bound reported beside it. Where lifting it
    # would lower the RMSE by 2 %, the candidate strains the base model; where the interval stays
    # below the plausible range (a membrane a load cell's offset replaced on a null: [0, 0.036]),
    # the data say the value is implausible. Neither is named.
    p = problem()
    p.experiment.time_s = np.arange(ROWS, dtype=float)
    baseline = fit("none", {"force_N": np.full(ROWS, 5.0)}, [])
    baseline.coordinates = friction_scale_at(1.0)
    score = candidate("sensor_lag", 0.84, SHARED + 0.84).score
    at_zero = SimpleNamespace(
        value=lambda x: 1e-4,
        at_bound=lambda x, *tolerance: "lower",
        implausible=lambda v: not 0.1 <= v <= 10.0,
        bound_value=lambda side: 0.0,
        plausible=(0.1, 10.0),
        source="test",
    )
    for rmse_drop, interval, credible in (
        (8.5e-6, (0.0, 1.19), True),
        (0.02, (0.0, 1.19), False),
        (8.5e-6, (0.0, 0.036), False),
    ):
        lag = fit("sensor_lag", {"force_N": np.ones(ROWS)})
        lag.coordinates = {"friction_scale": (at_zero, 0.0)}
        lag.strain = {"friction_scale": (-0.136, rmse_drop)}
        lag.intervals = {"friction_scale": interval}
        j = judge(p, lag, score, baseline)
        assert j.credible is credible
        assert [f.parameter for f in (j.strain if credible else j.findings)] == ["friction_scale"]


def test_a_shift_is_placed_below_one_sample_only_by_its_interval():
    # within_resolution: a lag fitted below the 0.045 s the sampling resolves (0.9 of a 0.05 s
    # interval) whose 95 % interval reaches 0.045 s is not placed below it by the data; one whose
    # interval ends short of it is.
    p = problem()
    p.experiment.time_s = np.arange(ROWS) * 0.05
    lag = effect("sensor_lag", ["force_N"], EffectStage.measurement)
    lag.parameters = lambda: [SimpleNamespace(name="time_constant_s", resolution=Resolution.sample_interval)]
    for interval, reaches in (((0.041, 0.047), True), ((0.020, 0.040), False)):
        shifted = fit("sensor_lag", {"force_N": np.zeros(ROWS)}, [lag])
        shifted.params = {"time_constant_s": 0.044 if reaches else 0.03}
        shifted.intervals = {"time_constant_s": interval}
        assert unresolved(p, shifted) != []
        assert within_resolution(p, shifted) is reaches


def test_a_shift_of_one_whole_sample_fitted_a_hair_below_it_is_resolved():
    # A record one sample off fitted where the base model is not exact: 0.0497 s at a 0.05 s
    # interval (near-model bench, 0.96-1.00 of a sample) is resolved; an Arduino's channels read
    # 0.8 of an interval apart (bench_families' largest sub-sample skew) are not.
    p = problem()
    p.experiment.time_s = np.arange(ROWS) * 0.05
    skew = effect("time_skew", ["gauge_pressure_Pa"], EffectStage.measurement)
    skew.parameters = lambda: [SimpleNamespace(name="offset_s", resolution=Resolution.sample_interval)]
    for offset, resolved in ((0.0497, True), (-0.0497, True), (0.04, False), (-0.04, False)):
        shifted = fit("time_skew", {"gauge_pressure_Pa": np.zeros(ROWS)}, [skew])
        shifted.params = {"offset_s": offset}
        assert (unresolved(p, shifted) == []) is resolved, offset


def test_a_supplied_tests_transducer_error_that_implies_a_vacuum_is_an_objection(tmp_path):
    # A cyclic test pressurised from 0 kPa by a regulator (tests/independent/dmsp.py): a
    # transducer said to read 12 kPa high would have had the muscle at -12 kPa where it read 0.
    toml = write_dmsp_cyclic(tmp_path, DmspTruth(), gauge_kPa=400, stroke_m=0.01, cycles=1, seed=1)
    problem = SimpleNamespace(experiment=load_experiment(toml))
    (objection,) = holds_vacuum(problem, SimpleNamespace(effects=[catalog().parse("sensor_offset:offset_Pa=12000")]))
    assert "read 0 kPa" in objection and "-12 kPa" in objection
    assert holds_vacuum(problem, SimpleNamespace(effects=[catalog().parse("sensor_offset:offset_Pa=-12000")])) == []
    assert holds_vacuum(problem, SimpleNamespace(effects=[catalog().parse("slip_hysteresis")])) == []


def offset_at(name: str, value: float, plausible: tuple[float, float]):
    """An effect's offset as a coordinate, found at `value`, `plausible` its range (search unbounded)."""
    coordinate = SimpleNamespace(
        value=lambda x: value,
        at_bound=lambda x: None,
        implausible=lambda v: not plausible[0] <= v <= plausible[1],
        bound_value=lambda side: None,
        plausible=plausible,
        source="test",
    )
    return {name: (coordinate, 0.0)}


def sealed_case(name: str, gain: float):
    """A sealed test's force and pressure measured as zeros, its baseline predicting them, and a
    score of `gain` on both for candidate `name`: (problem, zeros, baseline, score)."""
    p = problem(("force_N", "gauge_pressure_Pa"))
    p.experiment.time_s = np.arange(ROWS, dtype=float)
    zeros = {c: np.zeros(ROWS) for c in p.channels}
    return p, zeros, fit("none", zeros, []), candidate(name, gain, SHARED + gain, channels=p.channels).score


def test_a_transducer_offset_beside_the_inflation_read_on_it_is_judged_by_its_interval():
    # A sealed test's pressure transducer reading 10 kPa high (bench_near_model, sensor_offset
    # strong, seed 3): the offset and the declared inflation pressure, read on that transducer,
    # share one reading, and the fit ended at 15.5 kPa with the inflation pressure 5 % low, beyond
    # the plausible 15 kPa but with 9.4-21.7 kPa its interval. Only an interval wholly outside says
    # the offset is implausible.
    p, zeros, baseline, score = sealed_case("offset", 0.9)
    cases = (
        ("gauge_pressure_Pa", "offset_Pa", 15.5e3, (-15e3, 15e3), (9.4e3, 21.7e3), True),
        ("gauge_pressure_Pa", "offset_Pa", 15.5e3, (-15e3, 15e3), (15.2e3, 16.0e3), False),
    )
    for channel, name, value, plausible, interval, credible in cases:
        instrument = effect("offset", [channel], EffectStage.measurement)
        instrument.parameters = lambda name=name: [SimpleNamespace(name=name, resolution=Resolution.any)]
        offset = fit("offset", zeros, [instrument])
        offset.coordinates = offset_at(name, value, plausible)
        offset.intervals = {name: interval}
        held = [f.parameter for f in judge(p, offset, score, baseline).findings]
        assert held == ([] if credible else [name])


def test_a_load_cell_offset_beside_the_bladders_modulus_is_judged_by_its_interval():
    # A load cell's offset and the bladder's modulus, calibrated beside it, split the force: on
    # another base model's membrane a -10 N offset was fitted beside a dead volume at -20.2 N, -23.0
    # to -17.5 N its interval (bench_near_model, dead_volume+load_cell strong, seed 25). Only an
    # interval wholly outside the plausible +-20 N says the offset is implausible (-25.7 N, -31.0 to
    # -20.3 N: load_cell strong, seed 17). With the modulus not calibrated beside it, or itself
    # ended outside its plausible range (0.09, a friction with memory read as a -24 N offset:
    # bench_families dahl, seed 2), the offset shares no reading and is held to its value; so it is
    # where nothing but the offset places the cell, its nonlinearity's interval holding zero (a
    # 20.04 N offset for a weak pressure offset: bench_near_model, sensor_offset weak, seed 25).
    # Alone or second in a pair, keyed as its fit keys it.
    p, zeros, baseline, score = sealed_case("load_cell", 0.5)
    placed, unplaced = (0.124, 0.134), (-0.021, 0.007)  # the nonlinearity's interval [1/kN]
    cases = (
        (-20.2, (-23.0, -17.5), 0.6, placed, True),
        (-20.2, (-23.0, -17.5), None, placed, False),
        (-20.2, (-23.0, -17.5), 0.09, placed, False),
        (-20.2, (-23.0, -17.5), 0.6, unplaced, False),
        (-25.7, (-31.0, -20.3), 0.6, placed, False),
    )
    for value, interval, modulus, nonlinearity, credible in cases:
        for first in ([], [effect("dead_volume", ["gauge_pressure_Pa"])]):
            load_cell = effect("load_cell", ["force_N"], EffectStage.measurement)
            load_cell.parameters = lambda: [
                SimpleNamespace(name=n, resolution=Resolution.any, neutral=0.0)
                for n in ("offset_N", "nonlinearity_per_kN")
            ]
            prefix = "load_cell." if first else ""
            name = prefix + "offset_N"
            offset = fit("load_cell", zeros, [*first, load_cell])
            offset.coordinates = offset_at(name, value, (-20.0, 20.0))
            if modulus is not None:
                offset.coordinates |= offset_at("bladder_scale", modulus, (0.33, 3.0))
            offset.intervals = {name: interval, prefix + "nonlinearity_per_kN": nonlinearity}
            held = [f.parameter for f in judge(p, offset, score, baseline).findings if f.parameter == name]
            assert held == ([] if credible else [name]), (value, modulus, nonlinearity, first)


def test_a_second_cause_must_resolve_the_structure_that_called_for_it():
    # A first cause leaving the force 2.07 times its noise (above PAIR_TRIGGER) calls for a second
    # (bench_near_model, sensor_lag seed 5: a friction with memory left it). A dead volume that
    # takes it only to 1.9 explains a share of a misfit it does not account for; one that takes it
    # within STRUCTURE_LEFT resolves it. A channel below PAIR_TRIGGER before did not call for the
    # pair, and is not held to it.
    p = problem(("force_N", "gauge_pressure_Pa"))
    single = fit("sensor_lag", {"force_N": np.full(ROWS, 2.07), "gauge_pressure_Pa": np.full(ROWS, 1.39)})
    assert 2.07 > PAIR_TRIGGER > 1.39
    for force, pressure, resolved in (
        (1.9, 1.0, False),
        (1.02 * STRUCTURE_LEFT, 1.0, False),
        (0.98 * STRUCTURE_LEFT, 1.0, True),
        (1.0, 1.6, True),
    ):
        pair = fit(
            "sensor_lag+dead_volume", {"force_N": np.full(ROWS, force), "gauge_pressure_Pa": np.full(ROWS, pressure)}
        )
        assert resolves(p, single, pair) is resolved


def test_a_pair_displaces_a_lone_cause_only_by_a_cause_worth_more():
    # bench_near_model, dead_volume+load_cell medium seed 2: compliant fibres alone gain 0.546; a
    # dead volume beside the load cell 0.648 on the same draws (0.22 of what the fibres leave),
    # and 0.629 the fibres beside the load cell (0.05 of what that leaves): the pair leads. A pair
    # ahead on every draw by less than MIN_GAIN of what the lone cause leaves (dead_volume medium
    # seed 1: a pressure offset beside the fibres, 0.689 against the dead volume's 0.686) adds no
    # cause's worth; one ahead by a cause's worth on its point but not on the draws adds no
    # evidence.
    lone = candidate("fiber_compliance", 0.546, 0.546 + SHARED)
    beside = candidate("fiber_compliance+load_cell", 0.629, 0.629 + SHARED + rng.normal(0, 0.005, SAMPLES))
    pair = candidate("dead_volume+load_cell", 0.648, 0.648 + SHARED + rng.normal(0, 0.005, SAMPLES))
    assert explains_more(pair, lone) and explains_more(pair, beside)
    assert gain_over(pair, beside) == pytest.approx(0.019 / 0.371)
    near = candidate("sensor_offset+fiber_compliance", 0.555, 0.555 + SHARED)
    assert 0.0 < gain_over(near, lone) < MIN_GAIN and not explains_more(near, lone)
    spread = candidate("dead_volume+load_cell", 0.648, 0.648 + SHARED + rng.normal(0, 0.08, SAMPLES))
    assert gain_over(spread, lone) >= MIN_GAIN and not explains_more(spread, lone)


def test_a_second_cause_the_data_leave_at_its_neutral_value_is_not_named():
    # bench_near_model load_cell strong seed 14: a dead volume of 0.15 % [0, 1.1 %] beside the load
    # cell gained 0.20 of its own, all of it the bladder's modulus refitted to nothing beside it.
    # Its interval holds 0, the volume that adds nothing: it is not there. Clear of it, it is.
    p = problem(("force_N", "gauge_pressure_Pa"))
    zeros = {c: np.zeros(ROWS) for c in p.channels}
    s = candidate("load_cell+dead_volume", 0.4, 0.4 + SHARED, channels=p.channels).score
    cell, volume, leak = (catalog().make(n) for n in ("load_cell", "dead_volume", "leak"))
    first = fit("load_cell", zeros, [cell])
    for band, there in (([0.0, 0.0113], False), ([0.001, 0.0113], True)):
        pair_fit = fit("load_cell+dead_volume", zeros, [cell, volume])
        pair_fit.intervals = {"load_cell.offset_N": [-24.1, -5.0], "dead_volume.volume_fraction": band}
        assert placed(pair_fit, volume) is there and placed(pair_fit, cell)
        assert second_holds(p, first, judge(p, pair_fit, s, fit("none", zeros, [])), s) is there
    # A leak's neutral time constant is infinity: an interval reaching it holds a leak of nothing.
    pair_fit = fit("load_cell+leak", zeros, [cell, leak])
    pair_fit.intervals = {"leak.time_constant_s": [2e3, np.inf]}
    assert not placed(pair_fit, leak)
    pair_fit.intervals = {"leak.time_constant_s": [80.0, 130.0]}
    assert placed(pair_fit, leak)
    # Nothing to judge it by (no interval, or values with no neutral one): not held at nothing.
    assert placed(fit("leak", zeros, [leak]), leak)


def test_a_load_cell_needs_more_gain_on_the_force_than_it_takes_of_a_misfit_not_its_own():
    # Where a load cell was named but was not in the data (bench_near_model seeds 1-24,
    # bench_families seeds 1-12), it gained 0.045-0.085 on the force in 10 of 15 namings. Judged
    # alone below MISREAD_GAIN it is not needed: not named, but a rival a cause may tie with
    # (marginal); beside a first cause, its own gain there is held to the same. No other effect
    # is, nor a pair judged against the baseline, whose gain is not the load cell's own.
    p = problem(("force_N", "gauge_pressure_Pa"))
    zeros = {c: np.zeros(ROWS) for c in p.channels}
    baseline = fit("none", zeros, [])
    load_cell = effect("load_cell", ["force_N"], EffectStage.measurement)
    others = [
        effect("sensor_offset", ["gauge_pressure_Pa"], EffectStage.measurement),
        effect("fiber_compliance", ["force_N"]),
        effect("sensor_lag", ["force_N"], EffectStage.measurement),
    ]
    others[-1].parameters = lambda: [SimpleNamespace(name="time_constant_s", resolution=Resolution.sample_interval)]
    for gain, founded in ((0.95 * MISREAD_GAIN, False), (1.05 * MISREAD_GAIN, True)):
        s = candidate("load_cell", gain, gain + SHARED, channels=p.channels).score
        assert (misread(p, s, [load_cell]) == []) is founded
        assert all(misread(p, s, [e]) == [] for e in others)
        alone = judge(p, fit("load_cell", zeros, [load_cell]), s, baseline)
        assert (alone.unneeded == []) is founded and alone.credible is founded
        assert marginal(alone) is not founded
        pair = judge(p, fit("leak+load_cell", zeros, [effect("leak"), load_cell]), s, baseline)
        assert pair.unneeded == []
        first = fit("leak", zeros, [effect("leak")])
        assert second_holds(p, first, pair, s) is founded
