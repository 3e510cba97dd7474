"""The diagnosis in the near-model world, as rates: data written by tests/independent/ (the
thesis's muscle written again, departing from pamkit's as a real muscle does — a wall that keeps
its thickness, another membrane law, Dahl or Coulomb friction, another end, a braid wound a few per
cent otherwise — every catalog cause hidden at its medium and strong strengths, and nulls), read by
`pamkit diagnose` as a user's files. bench/bench_near_model.py runs the whole world with its weak
strength and more nulls; this is its medium and strong strengths at three seeds (about a minute on
two cores).

A timid diagnosis (naming nothing where the base model is not exact) and a reckless one (naming
whatever absorbs the base model's misfit) both fail here."""

import sys
from concurrent.futures import ThreadPoolExecutor

import pytest
from conftest import SOURCE_DIR

from pamkit.diagnosis import diagnose, to_json
from pamkit.io.experiment import load_experiment

sys.path.insert(0, str(SOURCE_DIR / "tests"))  # tests/independent: a folder, not an installed package
import independent.near_families as near_families  # noqa: E402 (needs the path above)
from independent.near_families import FAMILIES  # noqa: E402

SEEDS = (1, 2, 3)
STRENGTHS = ("medium", "strong")
NULLS = (("null", 1), ("null", 2), ("null", 3), ("supplied_null", 1), ("supplied_null", 2))


MIN_RIGHT = 82
MAX_WRONG = 6


def named(report: dict) -> set[str]:
    return {c["effect"].split(":")[0] for c in report["causes"]}


@pytest.fixture(scope="module")
def world(tmp_path_factory):
    """Every dataset, diagnosed from its files: what was hidden, what was named, the verdict."""
    folder = tmp_path_factory.mktemp("near")
    cases = [
        (name, seed, strength)
        for name, family in FAMILIES.items()
        if family.hidden
        for strength in STRENGTHS
        for seed in SEEDS
    ]
    cases += [(name, seed, None) for name, seed in NULLS]

    def one(case):
        name, seed, strength = case
        dataset = FAMILIES[name].make(seed, folder / f"{name}-{seed}-{strength}", strength)
        report = to_json(diagnose(load_experiment(dataset.experiment), threads=1))
        return {
            "case": f"{name} {strength or ''} seed {seed}",
            "hidden": set(FAMILIES[name].hidden),
            "present": set(dataset.present),
            "named": named(report),
            "cause": report["cause"],
            "remainder": report["remainder"],
            "verdict": report["verdict"],
            "separation": report["separation"],
            "rejected": report["decision"]["rejected"],
            "name": name,
            "seed": seed,
            "strength": strength,
            "experiment": dataset.experiment,
        }

    with ThreadPoolExecutor(max_workers=2) as pool:
        return list(pool.map(one, cases))


def wrong(row) -> set[str]:
    return row["named"] - row["hidden"] - row["present"]


def lines(rows) -> str:
    return "\n".join(f"  {r['case']}: hidden {sorted(r['hidden'])}, named {sorted(r['named'])}" for r in rows)


def test_the_hidden_causes_are_named(world):
    rows = [r for r in world if r["hidden"]]
    right = [r for r in rows if r["hidden"] <= r["named"] and not wrong(r)]
    # The floor: the measured rate, 90 of 108 right (83 %; bench_near_model's medium and strong
    # strengths, seeds 1-3), less two binomial standard deviations (2 sqrt(108 * 0.83 * 0.17) = 7.8).
    # The aim, 90 %, is not reached: docs/validation.md lists the misses (a supplied transducer's
    # offset and gain at one held length are exactly a braid wound otherwise and a membrane's scale,
    # 1 of 6; a second cause the first's fit absorbs within the noise).
    assert len(right) >= MIN_RIGHT, f"{len(right)} of {len(rows)} named right; the others:\n" + lines(
        [r for r in rows if r not in right]
    )


def test_wrong_names_stay_rare(world):
    bad = [r for r in world if wrong(r)]
    # The target: at most 5 % of the world's datasets carry a wrong name (6 of 123; measured 3).
    assert len(bad) <= MAX_WRONG, f"wrong names:\n{lines(bad)}"


def test_nulls_name_nothing(world):
    # A null of a muscle that is not its declared build: `none` within the noise, or `unexplained`
    # with what is left as a remainder, never a cause.
    for r in (r for r in world if not r["hidden"]):
        assert not r["named"], r["verdict"]
        if r["cause"] == "unexplained":
            assert r["remainder"] and r["remainder"]["channels"], r["verdict"]


def test_a_first_cause_gives_way_where_its_rival_explains_more_beside_the_second(world):
    # A dead volume beside a load cell's error: alone, compliant fibres may win by taking a part of
    # the load cell's curvature. With the load cell named second, the dead volume fitted beside it
    # explains more (0.87 against 0.85 on strong seed 2) and leads in the fibres' place
    # (series/causes.py, _other_first). Where the fibres alone leave nothing that calls for a second
    # cause, the dead volume beside the load cell may still explain a cause's worth more than they
    # do, alone or beside it (medium seed 2: 0.648 against 0.546 and 0.629), and lead in their place
    # (rival_beside_a_second). The fibres are never named beside the load cell, and the dead volume
    # is, with it, at least twice (measured: twice; once before the second rule, never before both).
    rows = [r for r in world if r["name"] == "dead_volume+load_cell"]
    assert not any({"fiber_compliance", "load_cell"} <= r["named"] for r in rows), lines(rows)
    assert sum({"dead_volume", "load_cell"} <= r["named"] for r in rows) >= 2, lines(rows)


def test_the_test_a_report_asks_for_decides_beside_the_first(world, tmp_path):
    # Where one test cannot settle a cause (a tie, a cause narrowly ahead of a rival, an instrument's
    # error the data did not need), the report names the test that would (`separation`). That test,
    # written by the same generator on the same muscle, departures and causes (another inflation,
    # or the same stretches faster or slower), diagnosed beside the first as a campaign (a zero run:
    # the first again, zeroed by it), names no wrong cause and at least as many right as the first
    # alone.
    # A dead volume beside a load cell's error, which compliant fibres explain nearly as well, is
    # mostly named a dead volume with that test. Measured
    # (bench/bench_follow_up.py, these strengths at seeds 1-3): 8 such tests; alone 2 right and 2
    # wrong, with the test 2 right and none wrong; of the three dead volumes beside a load cell,
    # two named a dead volume and one nothing. (Before compliant fibres were inflated to their own
    # free length, they started every higher inflation pushing, and the tests run were 1.5 times
    # the pressure, where that third one named the dead volume too; at twice the pressure, now
    # asked for, its campaign names nothing.)
    rows = [
        r
        for r in world
        if r["separation"]
        and r["separation"]["separates"]
        and FAMILIES[r["name"]].kind == near_families.SEALED  # the generator writes variants of sealed tests
        and near_families.variant_asked(r["separation"]["test"])
    ]
    alone, with_test = [], []
    for r in rows:
        variant = near_families.variant_asked(r["separation"]["test"])
        second = FAMILIES[r["name"]].make(
            r["seed"], tmp_path / f"{r['name']}-{r['seed']}-{r['strength']}", r["strength"], variant
        )
        # a zero run is written beside the same test, which is diagnosed again, zeroed, alone
        tests = str(second.experiment) if variant.get("zero_run") else [str(r["experiment"]), str(second.experiment)]
        campaign = to_json(diagnose(tests, threads=2))
        alone.append(r["named"])
        with_test.append((r, named(campaign)))
        assert not wrong({**r, "named": with_test[-1][1]}), f"{r['case']} with {variant}: {campaign['verdict']}"
    right = lambda r, names: bool(r["hidden"]) and r["hidden"] <= names <= r["hidden"] | r["present"]  # noqa: E731
    assert len(rows) >= 4, lines(rows)
    assert sum(right(r, n) for r, n in with_test) >= sum(right(r, r["named"]) for r in rows), with_test
    pairs = [(r, n) for r, n in with_test if r["name"] == "dead_volume+load_cell"]
    assert sum("dead_volume" in n for _, n in pairs) >= 2, pairs  # and none wrong, as every test above


def test_an_instrument_refused_names_the_test_that_would_show_it(world):
    # A load cell's or a transducer's error that comes first but is not named (its offset beyond
    # what such an instrument plausibly reads beside the membrane's scale at its bound, its channel
    # left structured, or not needed where its channel was within the noise): one test cannot tell
    # what the instrument reads at nothing from what the muscle does, and the report names the test
    # on which the model with it and the calibrated model without it differ by at least twice the
    # noise (`separation.purpose = "check"`). Refused on its values, that test is the zero run,
    # which reads the instrument whatever the muscle. Measured at these strengths and seeds: 2 such
    # reports. A transducer's offset (sensor_offset medium seed 3) read as a load cell's -25 N
    # beside the membrane's scale at its bound asks for the zero run (it asked for nothing before);
    # a transducer not needed (strong seed 1) for an inflation to half the pressure.
    rows = [
        r
        for r in world
        if r["rejected"]
        and r["rejected"]["effect"] in ("load_cell", "sensor_offset")
        and r["cause"] in ("none", "unexplained")
        and not (r["separation"] and r["separation"]["purpose"] == "tie")
    ]
    zero_runs = 0
    for r in rows:
        s = r["separation"]
        assert s and s["purpose"] == "check" and s["separates"], (r["case"], r["verdict"])
        if not any("within the noise before it" in why for why in r["rejected"]["because"]):
            assert s["test"]["key"] == "zero_run" and "to check for" in r["verdict"], (r["case"], r["verdict"])
            zero_runs += 1
    assert len(rows) >= 2 and zero_runs >= 1, lines(rows)


def test_a_tie_alone_is_told_apart_beside_a_second(tmp_path):
    # A pressure transducer's time skew beside a slow leak: alone, a lag of the transducer (or a
    # fixture's play) opens the same loop and the two tie (neither named); beside the leak's drift
    # the skew leaves the pressure within its noise and the other, with its own best second, does not
    # (series/refused.py, tie_beside_a_second). Seeds 10-12, which the rates above do not hold:
    # measured 5 of 6 named right with the rule, 2 of 6 without (the sixth's skew alone is not
    # significant, so nothing ties); the floor leaves one to spare. Where the tie was broken the
    # report says from what.
    def one(case):
        seed, strength = case
        dataset = FAMILIES["leak+time_skew"].make(seed, tmp_path / f"{seed}-{strength}", strength)
        return to_json(diagnose(load_experiment(dataset.experiment), threads=1))

    with ThreadPoolExecutor(max_workers=2) as pool:
        reports = list(pool.map(one, [(seed, s) for seed in (10, 11, 12) for s in STRENGTHS]))
    right = [r for r in reports if named(r) == {"time_skew", "leak"}]
    assert len(right) >= 4, [r["verdict"] for r in reports]
    untied = [r for r in reports if r["decision"]["untied_from"]]
    loops = ("sensor_lag", "fixture_slack")
    assert untied and all(r["decision"]["untied_from"]["effect"].startswith(loops) for r in untied)
    assert all(any(f"alone, {other}" in r["verdict"] for other in loops) for r in untied)


def test_a_bound_that_costs_the_fit_nothing_leaves_a_cause_credible(tmp_path):
    # A supplied test's hose lag, or a braid gone slack, draws part of what the braid's friction drew,
    # and the joint fit rests the friction scale on its bound 0, where lifting the bound would lower
    # the fitted RMSE by less than 0.1 % (decide.judge). Seeds 4-6, which the rates above do not hold:
    # measured 6 of 6 named right with the rule, 4 of 6 without (refused for the friction at its
    # bound); the floor leaves one to spare. The verdict says where the friction rests.
    cases = [("supplied_sensor_lag", seed, "strong") for seed in (4, 5, 6)]
    cases += [("braid_slack", seed, "medium") for seed in (4, 5, 6)]

    def one(case):
        name, seed, strength = case
        dataset = FAMILIES[name].make(seed, tmp_path / f"{name}-{seed}-{strength}", strength)
        return name, to_json(diagnose(load_experiment(dataset.experiment), threads=1))

    with ThreadPoolExecutor(max_workers=2) as pool:
        reports = list(pool.map(one, cases))
    right = [r for name, r in reports if named(r) == set(FAMILIES[name].hidden)]
    assert len(right) >= 5, [r["verdict"] for _, r in reports]
    assert any(
        ", at a bound that costs the fit nothing: friction_scale" in r["verdict"] and "; with " in r["verdict"]
        for r in right
    )


def test_a_shift_of_one_whole_sample_is_named(tmp_path):
    # The weakest skews and lags the near-model world hides are one sample interval (0.05 s at
    # 20 Hz), a logger's record one sample off: fitted at 0.96-1.00 of a sample where the base model
    # is not exact, they are resolved from 0.9 of one (findings.RESOLVED_SHARE_OF_SAMPLE), and the
    # sampling's artefacts below that are not (bench_families' 0.2-0.8 of an interval). Seeds 1-3:
    # measured 6 of 9 named right with the share, 1 of 9 at a whole sample (those fitted a hair
    # above it), and no wrong name either way; the floor leaves one to spare.
    cases = [(name, seed) for name in ("time_skew", "sensor_lag", "supplied_sensor_lag") for seed in SEEDS]

    def one(case):
        name, seed = case
        dataset = FAMILIES[name].make(seed, tmp_path / f"{name}-{seed}", "weak")
        return name, to_json(diagnose(load_experiment(dataset.experiment), threads=1))

    with ThreadPoolExecutor(max_workers=2) as pool:
        reports = list(pool.map(one, cases))
    right = [r for name, r in reports if named(r) == set(FAMILIES[name].hidden)]
    assert len(right) >= 5, [r["verdict"] for _, r in reports]
    assert all(named(r) <= set(FAMILIES[name].hidden) for name, r in reports), [r["verdict"] for _, r in reports]
