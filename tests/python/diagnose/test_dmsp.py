"""Commercial muscles with their fibres in the membrane (Festo DMSP): the base physics of the
embedded construction (a braid that cannot push, end zones at flat flanges) and the friction
with memory (`slip_hysteresis`, Maxwell-slip) checked on data pamkit did not make: isometric,
isotonic and cyclic tests and campaigns of them, written by tests/independent/dmsp.py, its own
implementation of each; and on the datasheet's two numbers."""

import dataclasses
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from conftest import SOURCE_DIR

from pamkit import (
    BladderLaw,
    Construction,
    MuscleBuild,
    MuscleParams,
    fiber_revolutions_for_braid_angle,
    isotonic_lengths,
    static_forces,
)
from pamkit.diagnosis import diagnose, to_json, verdict

sys.path.insert(0, str(SOURCE_DIR / "tests"))  # tests/independent: a folder, not an installed package
from independent.dmsp import DmspTruth, write_dmsp_cyclic, write_dmsp_isometric, write_dmsp_isotonic  # noqa: E402

FESTO = SOURCE_DIR / "data" / "experiments" / "festo"
SEEDS = (21, 22, 23)
# Held-out error within 1.5 times the noise: the bar for data the model can describe.
WITHIN_NOISE = 1.5


def truth(seed: int) -> DmspTruth:
    """A DMSP-10-like muscle, its braid angle, end zones and friction drawn per seed."""
    rng = np.random.default_rng(seed)
    return DmspTruth(
        braid_angle_deg=float(rng.uniform(20.0, 25.0)),
        end_zone_m=float(rng.uniform(0.006, 0.010)),
        slip_force_N=float(rng.uniform(60.0, 200.0)),
        slip_distance_m=float(rng.uniform(0.01, 0.025)),
    )


# Two held lengths within the friction's break-away contraction (0.5-2.5 cm): each held out, the
# other tells how it loads there.
HELD_M = [0.25, 0.246, 0.241, 0.234, 0.225, 0.215]


def isometric(folder, t, seed):
    return write_dmsp_isometric(folder, t, lengths_m=HELD_M, top_kPa=600, seed=seed)


def isotonic(folder, t, seed):
    return write_dmsp_isotonic(folder, t, load_N=120.0, top_kPa=600, sweeps=3, seed=seed + 100)


def cyclic(folder, t, seed):
    # Shortened 25 mm from rest and returned three times at 4 bar: taut throughout, the loop the slip's.
    return write_dmsp_cyclic(folder, t, gauge_kPa=400, stroke_m=0.025, cycles=3, seed=seed + 200)


def within_intervals(fit, t: DmspTruth) -> dict[str, bool]:
    """Whether each calibrated number's jackknife interval holds its truth. The braid angle is
    pinned so closely (0.01 degrees) that the bias of pamkit's 16 slip elements against the
    independent model's 400 outweighs its spread: it is checked against the truth to 0.1 degree,
    a tenth of what a datasheet's angle can say, instead. For the same reason the slip force's
    interval is taken wider by the most the two discretisations' curves differ, f / (4 * 16^2)
    (muscle/slip.hpp: 16 elements' curve is the continuous one's tangents, within that of it)."""
    expected = {"end_zone_m": t.end_zone_m, "slip_distance_m": t.slip_distance_m}
    out = {name: fit.intervals[name][0] <= value <= fit.intervals[name][1] for name, value in expected.items()}
    low, high = fit.intervals["slip_force_N"]
    discretisation = t.slip_force_N / (4 * 16**2)
    out["slip_force_N"] = low - discretisation <= t.slip_force_N <= high + discretisation
    out["braid_angle_deg"] = abs(fit.params["braid_angle_deg"] - t.braid_angle_deg) <= 0.1
    return out


def test_isometric_sweeps_name_the_slip_and_carry_to_held_lengths_left_out(tmp_path):
    # Each held length pressurised to 6 bar and vented twice, from rest: below the rest length the
    # muscle contracts slack until taut, and keeps what its friction took up. Three seeds: the
    # slip is named on each, held out within 1.5x the noise.
    named, ratios = 0, []
    for seed in SEEDS:
        t = truth(seed)
        d = diagnose(isometric(tmp_path / f"s{seed}", t, seed), threads=2)
        report = to_json(d)
        named += d.cause == "slip_hysteresis"
        ratios.append(report["extended"]["heldout_rmse"]["force_N"] / d.noise["force_N"])
        assert report["baseline"]["heldout_rmse"]["force_N"] > 10 * d.noise["force_N"], verdict(d)
    assert named == len(SEEDS), ratios
    assert max(ratios) <= WITHIN_NOISE, ratios


# What stretches in series with the braid (fittings, load cell, frame): 4 um/N, about what the
# published DMSP-10-250 map calibrates (docs/validation.md).
SERIES_COMPLIANCE = 4e-6
SERIES_UNKNOWN = "series_compliance_m_per_N = [0.0, 2e-5]\n"


def test_a_series_compliance_declared_unknown_is_recovered_and_left_rigid_bends_the_braid(tmp_path):
    # Each held length's braid lies c F short of it, so the force flattens where it is steep (near
    # rest, at high pressure), and a held muscle's friction follows what the pull moves it. With the
    # compliance unknown in [calibrate] the map recovers it within its jackknife interval, the braid
    # angle within 0.1 degree (within_intervals' bar) and every held length within the noise held
    # out, on each seed (measured 0.78-0.97x); declared rigid, the braid angle and the friction
    # absorb what they can and the braid angle ends more than 0.1 degree off (measured 0.45-1.08,
    # held out 2.0-3.6x the noise) on each.
    for seed in SEEDS:
        t = dataclasses.replace(truth(seed), series_compliance_m_per_N=SERIES_COMPLIANCE)
        held = isometric(tmp_path / f"rigid{seed}", t, seed)
        d = diagnose(held, threads=2)
        assert abs(d.extended.params["braid_angle_deg"] - t.braid_angle_deg) > 0.1, verdict(d)
        assert to_json(d)["extended"]["heldout_rmse"]["force_N"] > WITHIN_NOISE * d.noise["force_N"], verdict(d)
        free = write_dmsp_isometric(
            tmp_path / f"free{seed}", t, lengths_m=HELD_M, top_kPa=600, seed=seed, calibrate=SERIES_UNKNOWN
        )
        d = diagnose(free, threads=2)
        report = to_json(d)
        assert d.cause == "slip_hysteresis", verdict(d)
        low, high = d.extended.intervals["series_compliance_m_per_N"]
        assert low <= SERIES_COMPLIANCE <= high, verdict(d)
        assert abs(d.extended.params["braid_angle_deg"] - t.braid_angle_deg) <= 0.1, verdict(d)
        assert report["extended"]["heldout_rmse"]["force_N"] <= WITHIN_NOISE * d.noise["force_N"], verdict(d)


def test_a_loop_at_one_held_length_is_the_muscle_s_not_the_load_cell_s_noise(tmp_path):
    # Held at one length (at rest, or 5 mm short) with 15 um/N in series (the search reaches 20),
    # the braid moves with the pull and its friction opens a loop between pressurising and venting.
    # The table's noise is what the load cell adds (1 N read in 0.1 N steps: within 25 %, measured
    # 0.90-1.18 N), not the loop (pooled across the branches it read 4.7 N on the first of these);
    # so a model that has no loop there is not `none` (held out 6.4-19.9 N off), and with the
    # compliance unknown the slip is named.
    for seed in SEEDS:
        t = dataclasses.replace(truth(seed), series_compliance_m_per_N=1.5e-5)
        for held, sweeps in ((t.rest_length_m, 2), (t.rest_length_m - 0.005, 3)):
            d = diagnose(
                write_dmsp_isometric(
                    tmp_path / f"{seed}-{sweeps}", t, lengths_m=[held], top_kPa=600, seed=seed, sweeps=sweeps
                )
            )
            assert 0.8 <= d.noise["force_N"] <= 1.25, verdict(d)
            assert d.cause != "none", verdict(d)
        free = write_dmsp_isometric(
            tmp_path / f"free{seed}", t, lengths_m=[t.rest_length_m], top_kPa=600, seed=seed, calibrate=SERIES_UNKNOWN
        )
        d = diagnose(free)
        assert d.cause == "slip_hysteresis", verdict(d)


# A lab's first isometric test of a cut muscle (a DMSP-10 cut to 10 or 40 cm): held at one length,
# pressurised in 25 kPa steps to 6 bar and vented, once or twice. Mounted 1.5 % short of its rest
# length (kinked, or the clamps' play) it contracts slack until taut and its friction keeps what
# it took up; held straight at its rest length its braid never moves.
CUT_M = (0.10, 0.40)
MOUNTED_SHORT = 0.015


def test_one_held_length_names_the_slip_where_the_muscle_moved_and_nothing_where_it_did_not(tmp_path):
    # Fewer than three held lengths: each pressure run, or with one sweep each half of it, is held
    # out (diagnosis/tables/kinds.py, map_groups). The bar is the near-model world's: 90 % of the
    # moved muscles named, no wrong name (measured 12 of 12 here, 24 of 24 over seeds 21-26). At 10
    # cm the friction's take-up and a transducer reading 12 kPa high draw the same line; the rows
    # read at 0 kPa after venting refuse the transducer (the muscle would have held a vacuum).
    named, wrong, straight = 0, [], []
    for seed in SEEDS:
        for cut in CUT_M:
            for sweeps in (1, 2):
                t = dataclasses.replace(truth(seed), rest_length_m=cut)
                folder = tmp_path / f"{seed}-{cut}-{sweeps}"
                short = [cut * (1 - MOUNTED_SHORT)]
                d = diagnose(
                    write_dmsp_isometric(folder / "short", t, lengths_m=short, top_kPa=600, seed=seed, sweeps=sweeps)
                )
                named += d.cause == "slip_hysteresis"
                if d.cause not in ("slip_hysteresis", "unexplained", "none"):  # a miss, not a wrong name
                    wrong.append(verdict(d))
                d = diagnose(
                    write_dmsp_isometric(folder / "rest", t, lengths_m=[cut], top_kPa=600, seed=seed, sweeps=sweeps)
                )
                straight.append(d.cause)
    runs = len(SEEDS) * len(CUT_M) * 2
    assert named >= 0.9 * runs and not wrong, (named, wrong)
    assert straight == ["none"] * runs, straight


# The laser's noise tests/independent/dmsp.py draws on an isotonic test's lengths [m].
LASER_NOISE_M = 0.1e-3


def test_an_isotonic_test_of_one_or_two_sweeps_names_the_slip_and_nothing_without_it(tmp_path):
    # A lab's first isotonic test: the load hung on, the pressure stepped to 6 bar and back once or
    # twice. Fewer than three sweeps: each pressure run, or with one sweep each half of it, is held
    # out (diagnosis/tables/kinds.py, held_out_units). The bar is the near-model world's: 90 % of
    # the muscles with friction named and no wrong name (measured 6 of 6 here, 24 of 24 over seeds
    # 21-32 of another draw); without friction (the sweeps from 2 bar: vented, nothing holds the
    # load) `none` on 90 % (measured 6 of 6). The held-out length within the 1.5 mm a real rig's
    # sweeps are judged by (measured 0.10-0.47 mm), and the noise, told without the model from four
    # rows at a time, within 40 % of the laser's on each test (measured 0.07-0.12 mm for 0.1).
    named, wrong, nulls, noise = 0, [], [], []
    for seed in SEEDS:
        for sweeps in (1, 2):
            t = truth(seed)
            friction = write_dmsp_isotonic(
                tmp_path / f"{seed}-{sweeps}", t, load_N=120.0, top_kPa=600, sweeps=sweeps, seed=seed
            )
            d = diagnose(friction)
            noise.append(d.noise["length_m"])
            named += d.cause == "slip_hysteresis"
            if d.cause not in ("slip_hysteresis", "unexplained", "none"):
                wrong.append(verdict(d))
            if d.cause == "slip_hysteresis":
                assert to_json(d)["extended"]["heldout_rmse"]["length_m"] <= 1.5e-3, verdict(d)
            still = dataclasses.replace(t, slip_force_N=0.0)
            d = diagnose(
                write_dmsp_isotonic(
                    tmp_path / f"null-{seed}-{sweeps}",
                    still,
                    load_N=120.0,
                    top_kPa=600,
                    sweeps=sweeps,
                    seed=seed,
                    bottom_kPa=200.0,
                )
            )
            nulls.append(d.cause)
            noise.append(d.noise["length_m"])
    runs = 2 * len(SEEDS)
    assert named >= 0.9 * runs and not wrong, (named, wrong)
    assert nulls.count("none") >= 0.9 * runs and set(nulls) <= {"none", "unexplained"}, nulls
    assert all(0.6 <= n / LASER_NOISE_M <= 1.4 for n in noise), noise


def test_a_second_effect_whose_values_hold_its_neutral_one_is_not_added(tmp_path):
    # One isotonic sweep (bench_families' dmsp_isotonic_one_sweep, seeds 1-12): beside the slip a
    # transducer's offset once gained 0.04 over it, its jackknife interval -23 to +1.8 kPa holding
    # the zero at which it adds nothing (seed 8). The data do not place it off zero, so it is not
    # added (tables/engine.py, _second_effect). Measured: the slip alone on 12 of 12 with the rule,
    # 11 of 12 without.
    from independent.families import dmsp_isotonic_one_sweep

    def one(seed):
        dataset = dmsp_isotonic_one_sweep(seed, tmp_path / str(seed))
        return [c["effect"] for c in to_json(diagnose(dataset.experiment, threads=1))["causes"]]

    with ThreadPoolExecutor(max_workers=2) as pool:
        named = list(pool.map(one, range(1, 13)))
    assert all(n == ["slip_hysteresis"] for n in named), named


def test_a_straight_and_a_short_mounted_test_of_one_muscle_calibrate_it_together(tmp_path):
    # The lab's pair: the cut muscle held straight at its rest length and mounted short, diagnosed
    # as one campaign. The bar is the near-model world's 90 % of the slip named (measured 6 of 6);
    # where named, each test is predicted by the muscle calibrated on the other alone within 1.5x
    # the noise (measured 0.83-1.07x) and the braid angle, which the straight test's slope fixes,
    # within 0.1 degree of its truth (measured 0.006).
    named = 0
    for seed in SEEDS:
        for cut in CUT_M:
            t = dataclasses.replace(truth(seed), rest_length_m=cut)
            folder = tmp_path / f"{seed}-{cut}"
            tests = [
                write_dmsp_isometric(folder / name, t, lengths_m=[held], top_kPa=600, seed=seed)
                for name, held in (("straight", cut), ("short", cut * (1 - MOUNTED_SHORT)))
            ]
            d = diagnose(tests, threads=2)
            if d.cause != "slip_hysteresis":
                continue
            named += 1
            ratios = [errors["force_N"]["heldout_rmse"] / errors["force_N"]["noise"] for errors in d.by_test.values()]
            assert max(ratios) <= WITHIN_NOISE, (ratios, verdict(d))
            assert abs(d.extended.params["braid_angle_deg"] - t.braid_angle_deg) <= 0.1, verdict(d)
    assert named >= 0.9 * len(SEEDS) * len(CUT_M), named


def test_a_map_read_high_by_its_transducer_names_the_offset_with_its_gain_held(tmp_path):
    # A frictionless map whose transducer reads 10 kPa high (the catalog's realistic 12 kPa): each
    # held length's line shifted in pressure. With its gain free the transducer was refused (gain
    # 0.65 beside the braid angle: 0 of 6 seeds of bench_families); held at 1, as a table cannot
    # tell it from the build, the offset is named in at least two of three seeds, the test_families
    # bar (measured 3 of 3 here, 6 of 6 there), no other cause, and where named within 0.5 kPa
    # (measured 9.75-10.12 kPa) with the held gain said.
    named = 0
    for seed in SEEDS:
        t = dataclasses.replace(truth(seed), slip_force_N=0.0)
        d = diagnose(
            write_dmsp_isometric(
                tmp_path / str(seed), t, lengths_m=HELD_M, top_kPa=600, seed=seed, pressure_offset_kPa=10.0
            )
        )
        assert d.cause in ("sensor_offset", "none", "unexplained"), verdict(d)
        if d.cause != "sensor_offset":
            continue
        named += 1
        (cause,) = to_json(d)["causes"]
        assert cause["params"]["offset_Pa"] == pytest.approx(10e3, abs=0.5e3), verdict(d)
        assert cause["held"] == {"gain": 1.0} and "gain = 1 (held" in verdict(d)
    assert named >= 2, named


# One held length within the friction's break-away contraction (5 mm, the distance 10-25 mm): the
# others contract past it (35, 45 mm) or not at all (the rest length), and none of them tells it.
ONE_WITHIN_M = [0.25, 0.245, 0.215, 0.205]


def test_a_held_length_that_alone_tells_a_value_says_so_when_held_out(tmp_path, monkeypatch):
    # Held out, that length is predicted with a break-away distance the others leave open: its
    # error is the experiment's design, and the remainder says which value it rests on. The whole
    # fit, which all lengths inform, still finds the truth (a refit without one length that fits
    # better is tried as the whole fit's start: the declared distance's basin is not the truth's).
    for seed in SEEDS:
        t = truth(seed)
        d = diagnose(write_dmsp_isometric(tmp_path / f"s{seed}", t, lengths_m=ONE_WITHIN_M, top_kPa=600, seed=seed))
        assert d.cause == "slip_hysteresis", verdict(d)
        where = to_json(d)["remainder"]["where"]["force_N"]
        assert where["group"] == "L=0.245" and where["rests_on"] == ["slip_distance_m"], verdict(d)
        assert "predicted with slip_distance_m, which the other held lengths do not determine" in verdict(d)
        assert all(within_intervals(d.extended, t).values()), (within_intervals(d.extended, t), verdict(d))
    # The figure says it beside that length's curve.
    import pamkit.diagnosis.tables.figure as table_figure

    drawn = []
    monkeypatch.setattr(table_figure, "save_figure", lambda figure, path: drawn.append(figure) or path)
    table_figure.plot(d, tmp_path / "map.png")
    labels = [text.get_text() for axis in drawn[0].axes if axis.get_legend() for text in axis.get_legend().get_texts()]
    assert "L=0.245 (held out: rests on slip_distance_m)" in labels, labels


def test_the_whole_fit_starts_again_from_a_refit_that_found_a_deeper_basin(tmp_path):
    # Three held lengths of one DMSP-10 (the default truth), twelve noise seeds. From the declared
    # start the friction's fit settles at long end zones and a short break-away distance on some
    # seeds, twice the truth's cost; a refit without one length may find the truth's basin, and
    # the whole fit is tried from there. Counted: seeds whose whole fit reaches the truth's basin
    # (its cost within 1 % of a fit started at the truth), with the refits' start and from the
    # declared starts alone. Measured when it landed: 9 of 12 and 7 of 12.
    from concurrent.futures import ThreadPoolExecutor

    from pamkit.diagnosis.tables.fit import Fitter, TableModel, fit_table
    from pamkit.diagnosis.tables.kinds import campaign_of
    from pamkit.effects import catalog
    from pamkit.io.experiment import load_experiment

    t = DmspTruth()
    truth_values = {"braid_angle_deg": 22.0, "end_zone_m": 0.008, "slip_force_N": 150.0, "slip_distance_m": 0.02}
    with_restart = starts_alone = 0
    with ThreadPoolExecutor(2) as pool:
        for seed in range(1, 13):
            path = write_dmsp_isometric(tmp_path / f"s{seed}", t, lengths_m=[0.25, 0.235, 0.22], top_kPa=600, seed=seed)
            campaign = campaign_of([load_experiment(path)])
            model, used, channels = TableModel(campaign), ~campaign.censored, campaign.channels
            scales = {c: float(np.std(campaign.columns[c][used & campaign.predicts(c)])) for c in channels}
            make = [lambda: catalog().make("slip_hysteresis")]
            fitter, rows = Fitter(model, channels, scales, make), np.flatnonzero(used)
            truth_cost = fitter.cost(
                fitter.fit(rows, [np.array([c.of(truth_values[c.name]) for c in fitter.space])]), rows
            )
            fit = fit_table("slip", model, channels, scales, make, campaign.groups, used, pool)
            with_restart += fitter.cost(fit.x, rows) <= 1.01 * truth_cost
            starts_alone += fitter.cost(fitter.fit(rows, fitter.starts()), rows) <= 1.01 * truth_cost
    assert with_restart >= 9 and with_restart > starts_alone, (with_restart, starts_alone)


def test_a_campaign_of_an_isometric_and_an_isotonic_test_calibrates_one_muscle(tmp_path):
    # One muscle's isometric sweeps and isotonic sweeps (a weighed 120 N) calibrated at once, each
    # held length and each sweep predicted by the muscle fitted without it, within 1.5x each
    # channel's noise; the slip named, and every calibrated number's interval holding its truth,
    # on each seed.
    for seed in SEEDS:
        t = truth(seed)
        tests = [isometric(tmp_path / f"i{seed}", t, seed), isotonic(tmp_path / f"t{seed}", t, seed)]
        d = diagnose(tests, threads=2)
        report = to_json(d)
        assert d.cause == "slip_hysteresis", verdict(d)
        assert report["kind"] == "isometric_map + isotonic"
        for channel in ("force_N", "length_m"):
            assert report["extended"]["heldout_rmse"][channel] <= WITHIN_NOISE * d.noise[channel], verdict(d)
        assert all(within_intervals(d.extended, t).values()), (within_intervals(d.extended, t), verdict(d))


def test_one_muscle_across_the_three_characterisations_is_calibrated_once_and_predicts_each(tmp_path):
    # An isometric map, isotonic sweeps under a weighed load and a cyclic test on a tensile machine
    # of one muscle, calibrated at once: every held length, sweep and cycle predicted within 1.5x
    # its channel's noise by the muscle fitted without it, and each test by the muscle fitted on
    # the other two alone; the slip named, every calibrated number's interval holding its truth.
    # The three files go to the diagnosis as a user names them (pamkit diagnose a.toml b.toml c.toml).
    for seed in SEEDS:
        t = truth(seed)
        paths = [
            isometric(tmp_path / f"i{seed}", t, seed),
            isotonic(tmp_path / f"t{seed}", t, seed),
            cyclic(tmp_path / f"c{seed}", t, seed),
        ]
        d = diagnose([str(path) for path in paths], threads=2)
        report = to_json(d)
        assert d.cause == "slip_hysteresis", verdict(d)
        assert report["kind"] == "isometric_map + isotonic + cyclic"
        for channel in ("force_N", "length_m"):
            assert report["extended"]["heldout_rmse"][channel] <= WITHIN_NOISE * d.noise[channel], verdict(d)
        for name, channels in report["heldout_by_test"].items():
            for channel, errors in channels.items():
                assert errors["heldout_rmse"] <= WITHIN_NOISE * errors["noise"], (name, channel, verdict(d))
        assert sorted(report["heldout_by_test"]) == ["cyclic", "isometric", "isotonic"]
        assert all(within_intervals(d.extended, t).values()), (within_intervals(d.extended, t), verdict(d))


def test_one_muscle_with_a_series_compliance_across_the_three_characterisations(tmp_path):
    # The same three tests of a muscle with 4 um/N in series, each file declaring it unknown: held
    # lengths give c F, the load's sweeps c W, the cyclic test's held samples c F again. Calibrated
    # at once, the compliance is recovered within its interval (measured 3.98-4.00 um/N), with every
    # other number within its truth's; held out within 1.5x each channel's noise (measured force
    # 0.89-0.94x, length 0.93-1.18x). (Each test predicted by the other two alone: isometric
    # 0.86-0.99x, isotonic 1.08-1.34x, cyclic 0.87-1.69x.)
    for seed in SEEDS:
        t = dataclasses.replace(truth(seed), series_compliance_m_per_N=SERIES_COMPLIANCE)
        paths = [
            write_dmsp_isometric(
                tmp_path / f"i{seed}", t, lengths_m=HELD_M, top_kPa=600, seed=seed, calibrate=SERIES_UNKNOWN
            ),
            isotonic(tmp_path / f"t{seed}", t, seed),
            cyclic(tmp_path / f"c{seed}", t, seed),
        ]
        for path in paths[1:]:  # a campaign shares its unknowns
            path.write_text(path.read_text().replace("[calibrate]\n", "[calibrate]\n" + SERIES_UNKNOWN, 1))
        d = diagnose([str(path) for path in paths], threads=2)
        report = to_json(d)
        assert d.cause == "slip_hysteresis", verdict(d)
        low, high = d.extended.intervals["series_compliance_m_per_N"]
        assert low <= SERIES_COMPLIANCE <= high, verdict(d)
        assert all(within_intervals(d.extended, t).values()), (within_intervals(d.extended, t), verdict(d))
        for channel in ("force_N", "length_m"):
            assert report["extended"]["heldout_rmse"][channel] <= WITHIN_NOISE * d.noise[channel], verdict(d)


def test_isotonic_sweeps_alone_open_loops_at_rest_that_the_slip_closes(tmp_path):
    # Settled steps under a weighed load: the loop between pressurising and venting is the
    # friction's (no rate in it). The slip is named on each seed, and the loop the calibrated
    # model predicts on held-out sweeps is the measured one.
    for seed in SEEDS:
        t = truth(seed)
        d = diagnose(isotonic(tmp_path / f"t{seed}", t, seed), threads=2)
        assert d.cause == "slip_hysteresis", verdict(d)
        measured, predicted = d.campaign.columns["length_m"], d.extended.heldout["length_m"]
        venting = d.campaign.branch < 0
        pressure = d.campaign.columns["gauge_pressure_Pa"]
        for p in (300e3, 450e3):  # the loop's width at two pressures, on the last sweep
            rows = (pressure == p) & (d.groups == d.groups.max())
            width = measured[rows & venting].mean() - measured[rows & ~venting].mean()
            assert width < -5 * 0.1e-3  # shorter on venting, by more than 5 times the laser's noise
            assert predicted[rows & venting].mean() - predicted[rows & ~venting].mean() == pytest.approx(
                width, abs=0.5e-3
            )
        # The first sweep starts from rest and reaches lengths no later sweep does: held out, the
        # later ones cannot place it, and the report says that is where the remainder lies; the
        # later sweeps, each predicted from sweeps like it, are held out within 1.5x the noise.
        where = to_json(d)["remainder"]["where"]["length_m"]
        assert where["group"] == "sweep 1" and where["rows_beyond"] > 0, verdict(d)
        assert where["others_ratio"] <= WITHIN_NOISE, verdict(d)


def dmsp20_truth(seed: int) -> DmspTruth:
    """A DMSP-20-like muscle (20 mm, 300 mm), its braid angle, end zones and friction drawn per seed."""
    rng = np.random.default_rng(seed)
    return DmspTruth(
        rest_length_m=0.3,
        diameter_m=0.02,
        braid_angle_deg=float(rng.uniform(22.0, 26.0)),
        end_zone_m=float(rng.uniform(0.012, 0.020)),
        slip_force_N=float(rng.uniform(150.0, 400.0)),
        slip_distance_m=float(rng.uniform(0.012, 0.03)),
    )


def test_a_dmsp20_meets_the_real_data_targets(tmp_path):
    # The targets real sweeps of commercial muscles are judged on (a rig that repeats to 0.8 mm),
    # at the DMSP-20's size: isometric sweeps held out within 5 % of the force's span, isotonic
    # sweeps under a weighed 480 N held out within 1.5 mm RMSE on each branch, the loops named,
    # and no force below zero, the written-out muscle's included, on each seed.
    from pamkit import BraidGeometry, read_muscle_params
    from pamkit.diagnosis.params_out import write_params

    held = [0.3, 0.295, 0.289, 0.281, 0.27, 0.258]  # the DMSP-10 tests' held lengths, scaled
    for seed in SEEDS:
        t = dmsp20_truth(seed)
        d = diagnose(write_dmsp_isometric(tmp_path / f"i{seed}", t, lengths_m=held, top_kPa=600, seed=seed), threads=2)
        assert d.cause == "slip_hysteresis", verdict(d)
        force = d.campaign.columns["force_N"]
        error = np.nanmax(np.abs(d.extended.heldout["force_N"] - force))
        assert error <= 0.05 * (force.max() - force.min()), verdict(d)
        assert np.nanmin(d.extended.heldout["force_N"]) >= 0.0
        write_params(d, tmp_path / f"muscle{seed}.toml")
        params = read_muscle_params(str(tmp_path / f"muscle{seed}.toml"))
        geometry = BraidGeometry(params.build)
        lengths = np.linspace(geometry.min_length * 1.01, geometry.max_length * 0.99, 60)
        for pressure in (0.0, 300e3, 600e3):  # [Pa]
            assert static_forces(params, lengths, np.full(lengths.size, pressure)).min() >= 0.0
        path = write_dmsp_isotonic(tmp_path / f"t{seed}", t, load_N=480.0, top_kPa=600, sweeps=3, seed=seed + 100)
        d = diagnose(path, threads=2)
        assert d.cause == "slip_hysteresis", verdict(d)
        residual = d.extended.heldout["length_m"] - d.campaign.columns["length_m"]
        for branch in (1, -1):
            on = d.campaign.branch == branch
            assert np.sqrt(np.nanmean(residual[on] ** 2)) <= 1.5e-3, (branch, verdict(d))


def test_without_friction_the_slip_is_not_named(tmp_path):
    # The same isometric sweeps of a muscle without friction: nothing hidden, nothing named.
    causes = []
    for seed in SEEDS:
        t = truth(seed)
        t.slip_force_N = 0.0
        d = diagnose(isometric(tmp_path / f"n{seed}", t, seed), threads=2)
        causes.append(d.cause)
    assert causes.count("slip_hysteresis") == 0, causes
    assert causes.count("none") == len(SEEDS), causes


def test_no_prediction_of_an_embedded_muscle_pushes_and_the_written_muscle_keeps_its_construction(tmp_path):
    # A Festo map's diagnosis, its calibrated muscle written out (`--params-out`), read back: held
    # anywhere in the braid's range at any pressure, slack or taut, it never pushes.
    from pamkit import BraidGeometry, read_muscle_params
    from pamkit.diagnosis.params_out import write_params

    d = diagnose(FESTO / "DMSP-10-250.toml", threads=2)
    assert np.nanmin(d.extended.heldout["force_N"]) >= 0.0
    assert np.nanmin(d.baseline.heldout["force_N"]) >= 0.0
    write_params(d, tmp_path / "dmsp.toml")
    assert "construction = 'embedded'" in (tmp_path / "dmsp.toml").read_text()
    params = read_muscle_params(str(tmp_path / "dmsp.toml"))
    assert params.build.construction == Construction.embedded
    geometry = BraidGeometry(params.build)
    lengths = np.linspace(geometry.min_length * 1.01, geometry.max_length * 0.99, 60)
    for pressure in (0.0, 50e3, 300e3, 600e3):  # [Pa]
        assert static_forces(params, lengths, np.full(lengths.size, pressure)).min() >= 0.0


def datasheet_build(braid_angle_deg: float, end_zone_m: float) -> MuscleParams:
    build = MuscleBuild(
        length_m=0.25,
        diameter_m=0.01,
        bladder_diameter_m=0.01,
        bladder_thickness_m=0.5e-3,
        fiber_thickness_m=0.0,
        end_diameter_m=0.005,
        cone_generator_m=0.0,
        end_zone_m=end_zone_m,
    )
    build.construction = Construction.embedded
    build.fiber_revolutions = fiber_revolutions_for_braid_angle(build, braid_angle_deg)
    return MuscleParams(build=build, bladder=BladderLaw.none())


def datasheet_numbers(params: MuscleParams) -> tuple[float, float]:
    """Force at rest and 6 bar [N]; free contraction at 6 bar, inflated from rest [1]."""
    force = float(static_forces(params, np.array([0.25]), np.array([600e3]))[0])
    free = float(isotonic_lengths(params, np.array([600e3]), 0.0, 0.25).length_m[0])
    return force, 1.0 - free / 0.25


def test_the_datasheet_force_and_contraction_hold_together_only_with_the_embedded_physics():
    # The DMSP-10's datasheet: 630 N at 6 bar at rest, 25 % contraction at 6 bar. The force at rest
    # fixes the braid angle alone (nothing has moved: no friction taken up yet). With the thesis's
    # force-contraction law that angle contracts the free muscle 36 %, and the angle that contracts
    # it 25 % gives a force far from 630 N. With the end zones (0.8 braid diameters, both Festo
    # maps' pressure slopes) and the friction the free muscle takes up as it contracts, a slip
    # force inside the catalog's plausible range meets the contraction too.
    from scipy.optimize import brentq

    def numbers(angle, end_zone_m=0.008, slip_N=0.0):
        params = datasheet_build(angle, end_zone_m)
        params.extensions.slip_force_N = slip_N
        params.extensions.slip_distance_m = 0.02
        return datasheet_numbers(params)

    angle = brentq(lambda a: numbers(a)[0] - 630.0, 10.0, 45.0, xtol=1e-6)
    slip = brentq(lambda f: numbers(angle, slip_N=f)[1] - 0.25, 0.0, 1000.0, xtol=1e-3)
    force, contraction = numbers(angle, slip_N=slip)
    # Within 1 %: unloaded, the free muscle stops where its force passes the slack braid's 1 N band.
    assert force == pytest.approx(630.0, rel=0.01) and contraction == pytest.approx(0.25, rel=0.01)
    assert 15.0 <= angle <= 30.0 and 0.0 < slip <= 1000.0
    thesis_force_angle = brentq(lambda a: numbers(a, 0.0)[0] - 630.0, 10.0, 45.0, xtol=1e-6)
    assert numbers(thesis_force_angle, 0.0)[1] > 0.3  # the thesis's law: far more than 25 %
    thesis_contraction_angle = brentq(lambda a: numbers(a, 0.0)[1] - 0.25, 25.0, 50.0, xtol=1e-6)
    assert numbers(thesis_contraction_angle, 0.0)[0] < 0.7 * 630.0  # and then far less than 630 N
