"""The test a tie asks for (pamkit/diagnosis/series/separate.py): where two candidates explain one
sealed test alike, the diagnosis names a test on the same muscle that parts them. Checked on data
pamkit did not make (tests/independent): the test it names, run on the independent muscle, decides
for the cause that is there."""

import sys
from dataclasses import replace

import numpy as np
import pytest
import tomllib
from conftest import SOURCE_DIR

from pamkit import Report
from pamkit.diagnosis import diagnose, to_json, verdict
from pamkit.diagnosis.series.decide import Cause
from pamkit.diagnosis.series.separate import AS_RUN, SEPARATES, VARIANTS, _run, separating_test
from pamkit.effects import catalog

sys.path.insert(0, str(SOURCE_DIR / "tests"))  # tests/independent: a folder, not an installed package
from independent.families import independent_dead_volume, isometric_null, sealed_test  # noqa: E402
from independent.physics import Build, Motion, Physics, SealedMuscle  # noqa: E402

# bench_families: a dead volume ties with stretching fibres on 3 of 3 seeds (both lower the
# pressure's swing in a sealed stretch; their held-out gains agree to 0.004), and over these six
# with another candidate on 5.
SEEDS = range(1, 7)


@pytest.fixture(scope="module")
def dead_volumes(tmp_path_factory):
    folder = tmp_path_factory.mktemp("dead_volume")
    out = []
    for seed in SEEDS:
        dataset = independent_dead_volume(seed, folder / str(seed))
        out.append((dataset, diagnose(str(dataset.experiment), threads=2)))
    return out


def _second_test(dataset, d, folder):
    """The test the tie named, run on the same independent muscle (its plan redrawn from the same
    seed, but for the inflation pressure, set to 0.01 kPa as a regulator is)."""
    pressure_kPa = round(
        d.separation.variant.describe(d.separation.declared_Pa)["inflation_gauge_pressure_Pa"] / 1e3, 2
    )
    seed = int(dataset.experiment.parent.name)
    physics = Physics(dead_volume_fraction=dataset.truth["volume_fraction"])
    return sealed_test(
        seed, folder, physics=physics, plan_change=lambda plan, rng: replace(plan, gauge_kPa=pressure_kPa)
    )


def _truth_on(dataset, d, variant) -> dict[str, np.ndarray]:
    """The independent muscle (its true dead volume) on `variant`, a free inflation at a
    pressure of its own: what the lab would measure, without noise."""
    test = tomllib.loads(dataset.experiment.read_text())["test"]
    pressure_kPa = variant.describe(d.separation.declared_Pa)["inflation_gauge_pressure_Pa"] / 1e3
    muscle = SealedMuscle(
        Build(),
        Physics(dead_volume_fraction=dataset.truth["volume_fraction"]),
        pressure_kPa,
        test["ambient_temperature_C"],
    )
    motion = d.problem.predictor.motion
    time = np.asarray(motion.time_s)
    run = muscle.run(Motion(time, np.asarray(motion.elongation_m)), time)
    return {"force_N": run.force_N, "gauge_pressure_Pa": run.gauge_kPa * 1e3}


def _off(d, fit, variant, truth) -> float:
    """How far `fit`'s prediction on `variant` lies from `truth`: the largest channel's RMS over
    its noise."""
    m = _run(d.problem, fit, variant)
    return max(
        float(np.sqrt(np.mean(((np.asarray(getattr(m, c)) - truth[c]) / d.problem.sigma[c]) ** 2))) for c in truth
    )


def test_the_test_named_for_a_tie_decides_for_the_cause_that_is_there(dead_volumes):
    # Each tie of the dead volume with another candidate (stretching fibres on four seeds, a load
    # cell's error on one) names a test; run on the independent muscle, its truth lies nearer the
    # dead volume's prediction, and the other's is off by at least SEPARATES (so the test rules it
    # out). Raising the inflation parts them: the fibres' stretch grows with the pressure, a dead
    # volume's share of the gas does not.
    ties = 0
    for dataset, d in dead_volumes:
        s = d.separation
        if s is None or s.purpose != "tie":
            continue
        ties += 1
        assert "dead_volume" in s.between, verdict(d)
        other = next(name for name in s.between if name != "dead_volume")
        assert s.separates and s.variant.pressure_share != 0.0, s.to_json()
        assert max(s.here.values()) < SEPARATES  # on the test as run they are not apart: a tie
        fits = {j.fit.name: j.fit for j in d.candidates}
        truth = _truth_on(dataset, d, s.variant)
        right, wrong = _off(d, fits["dead_volume"], s.variant, truth), _off(d, fits[other], s.variant, truth)
        assert right < wrong and wrong >= SEPARATES, (dataset.truth, other, right, wrong)
        # The verdict says it in the file's units, the JSON in SI.
        assert "inflated freely to" in verdict(d) and "kPa and sealed" in verdict(d)
        assert to_json(d)["separation"]["test"]["inflation_gauge_pressure_Pa"] > 0.0
        assert Report(to_json(d)).separation == to_json(d)["separation"]
    assert ties >= 4, ties  # measured: 5 of 6 (seed 3 leaves structure that neither explains)


def test_two_fits_alike_are_apart_on_no_variant(dead_volumes):
    # An invariant: a fit against itself differs by nothing on any variant.
    _, d = next(
        (dataset, d) for dataset, d in dead_volumes if d.separation is not None and d.separation.purpose == "tie"
    )
    fit = d.candidates[0].fit
    s = separating_test(d.problem, fit, fit)
    assert not s.separates
    assert all(v == 0.0 for v in s.tried.values()) and set(s.tried) == {v.key for v in VARIANTS}


def test_a_supplied_sweep_has_variants_of_its_own(tmp_path):
    # A supplied sweep's variants are its pressure raised and lowered at every sample, the same
    # sweep faster and slower, and a zero run: each runs on an independent isometric sweep, and two
    # fits alike are apart on none of them.
    d = diagnose(str(isometric_null(1, tmp_path).experiment), threads=2)
    s = separating_test(d.problem, d.baseline, d.baseline)
    assert s.declared_Pa is None and not s.separates
    assert set(s.tried) == {v.key for v in VARIANTS} and all(v == 0.0 for v in s.tried.values()), s.tried
    assert "supplied pressure 50% higher" in replace(s, variant=VARIANTS[0]).test_phrase()


def test_a_higher_inflation_is_set_by_what_the_transducer_reads(dead_volumes):
    # The lab inflates until its transducer reads half the declared pressure again: whatever the
    # fit's transducer (here one reading 4 kPa high and 10 % steep), the first reading of the
    # variant is the test's first reading plus that change; the gas's own pressure moves by the
    # change over the transducer's gain.
    _, d = dead_volumes[0]
    higher = next(v for v in VARIANTS if v.pressure_share > 0)
    change_Pa = higher.pressure_share * d.problem.experiment.inflation_gauge_pressure_Pa
    transducer = catalog().parse("sensor_offset:offset_Pa=4000,gain=1.1")
    for fit in (d.baseline, replace(d.baseline, effects=[transducer])):
        first = [np.asarray(_run(d.problem, fit, v).gauge_pressure_Pa)[0] for v in (AS_RUN, higher)]
        assert first[1] - first[0] == pytest.approx(change_Pa, rel=1e-6)


def test_a_zero_run_reads_a_transducers_offset(dead_volumes):
    # The zero run: a vented, unloaded muscle, which a pressure offset reads as itself.
    _, d = dead_volumes[0]
    offset_Pa = 4000.0
    plain = d.baseline
    shifted = replace(plain, effects=[catalog().parse(f"sensor_offset:offset_Pa={offset_Pa}")])
    zero = next(v for v in VARIANTS if v.zero_reading)
    reading = np.asarray(_run(d.problem, shifted, zero).gauge_pressure_Pa)
    assert reading == pytest.approx(offset_Pa)
    assert np.asarray(_run(d.problem, plain, zero).gauge_pressure_Pa) == pytest.approx(0.0)


def test_the_named_test_diagnosed_beside_the_first_breaks_the_tie(dead_volumes, tmp_path):
    # The whole loop a lab runs: the test the tie named, run on the independent muscle and diagnosed
    # with the first as a campaign (pamkit diagnose first.toml second.toml), names the dead volume:
    # carried from one test to the other on each test's baseline calibrated beside it, the dead
    # volume's one fraction gains on both (0.63-0.85), stretching fibres' two stiffnesses do not
    # agree (gains 0.04-0.20, or below zero). Measured: 4 of the 4 ties with stretching fibres.
    named = []
    for dataset, d in dead_volumes:
        if d.separation is None or "fiber_compliance" not in d.separation.between:
            continue
        second = _second_test(dataset, d, tmp_path / dataset.experiment.parent.name)
        campaign = diagnose([str(dataset.experiment), str(second.experiment)], threads=2)
        named.append(campaign.cause)
    assert len(named) >= 3, named
    assert named.count("dead_volume") >= len(named) - 1 and set(named) <= {"dead_volume", "unexplained"}, named


def test_a_cause_with_a_rival_close_behind_names_the_test_that_would_confirm_it(dead_volumes):
    # A cause named narrowly ahead of a rival (decide.close_rival) is reported with the rival and
    # the test that would confirm it; made here from a tie's two fits, the first named.
    _, d = next(
        (dataset, d) for dataset, d in dead_volumes if d.separation is not None and d.separation.purpose == "tie"
    )
    first, second = (next(j for j in d.candidates if j.fit.name == name) for name in d.separation.between)
    first.close_rival = second
    named = replace(
        d,
        decision=replace(d.decision, cause=first.fit.name, causes=[Cause(first.fit.name, first, first.score)]),
        extended=first.fit,
        extended_judgement=first,
        separation=separating_test(d.problem, first.fit, second.fit, "confirm"),
    )
    text = verdict(named)
    assert f"{second.fit.name} explains nearly as much" in text and f"to confirm {first.fit.name}" in text, text
    assert to_json(named)["separation"]["purpose"] == "confirm"


def test_a_zero_run_asked_for_is_written_with_what_to_do_with_it(dead_volumes, tmp_path, run_pamkit):
    # A report that asks for a zero run (to check for a transducer's offset: seed 3 of these) writes
    # what each explanation expects the instruments to read, and says where the run goes: beside
    # the test, named by its `[test] zero`.
    asking = [(dataset, d) for dataset, d in dead_volumes if d.separation and d.separation.variant.zero_reading]
    assert asking, [d.separation.to_json() if d.separation else None for _, d in dead_volumes]
    dataset, d = asking[0]
    done = run_pamkit("diagnose", dataset.experiment, "--quiet", "--next-test", tmp_path / "next.toml")
    assert done.returncode == 0, done.stderr
    assert f"wrote {tmp_path / 'next.predictions.csv'}" in done.stdout
    assert f"save them beside {dataset.experiment.name} and name them in its [test] (zero = " in done.stdout
    assert not (tmp_path / "next.toml").exists()
