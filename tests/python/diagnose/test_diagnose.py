"""Diagnosis as a user meets it: the report's keys (docs/reference/report.md), the command line, the Python
API, and bad input named by file, row and column."""

import json
import os
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from pamkit.diagnosis import diagnose, to_json, verdict
from pamkit.diagnosis.cycles import find_cycles, split_cycles
from pamkit.diagnosis.evidence import ljung_box_p, noise_scale
from pamkit.diagnosis.figure import series_figure
from pamkit.diagnosis.series.joint import calibrate_jointly
from pamkit.diagnosis.series.separate import ZERO_RUN, separating_test
from pamkit.effects import catalog
from pamkit.io.columns import value_from_si
from pamkit.io.guards import ExperimentError
from pamkit.synth.dataset import synthesize

SOURCE_DIR = Path(os.environ.get("PAMKIT_SOURCE_DIR", Path(__file__).resolve().parents[3]))
sys.path.insert(0, str(SOURCE_DIR / "tests"))  # tests/independent: a folder, not an installed package

from independent.families import mullins  # noqa: E402 (needs the path above)

REPORT_KEYS = {"baseline", "candidates", "cause", "extended", "gain", "gain_ci95", "residuals"}


@pytest.fixture(scope="module")
def leak_dataset(tmp_path_factory):
    # A leak strong enough to see (tau = 300 s against tests of one to several minutes).
    return synthesize("leak:time_constant_s=300", 5, tmp_path_factory.mktemp("leak"))


def test_report_has_the_design_keys_and_names_the_leak(leak_dataset, tmp_path, run_pamkit):
    report_path, plot_path = tmp_path / "r.json", tmp_path / "r.png"
    done = run_pamkit("diagnose", leak_dataset.experiment, "--json", report_path, "--plot", plot_path)
    assert done.returncode == 0, done.stderr
    assert "leak" in done.stdout and "gain" in done.stdout  # the one-line verdict
    assert "calibrating the baseline" in done.stderr  # progress on stderr
    report = json.loads(report_path.read_text())
    assert REPORT_KEYS <= set(report)
    assert report["cause"] == "leak"
    assert report["extended"]["effects"] == ["leak"]
    channels = set(report["baseline"]["rmse"])
    assert channels == {"force_N", "gauge_pressure_Pa", "temperature_K"}
    assert set(report["gain"]) == channels and set(report["gain_ci95"]) == channels
    for candidate in report["candidates"]:
        assert {"effect", "params", "heldout_rmse", "gain", "score"} <= set(candidate)
    assert set(report["residuals"]) == {"baseline", "extended"}
    assert set(report["residuals"]["baseline"]["ljung_box_p"]) == channels
    # The gain is the held-out RMSE's fractional reduction: recompute it from the report.
    for c in channels:
        expected = 1 - report["extended"]["rmse"][c] / report["baseline"]["rmse"][c]
        assert report["gain"][c] == pytest.approx(expected, rel=1e-9, abs=1e-12)
    # The truth (manifest) says 300 s; the fitted time constant lands near it.
    assert report["extended"]["params"]["time_constant_s"] == pytest.approx(300, rel=0.2)
    assert plot_path.read_bytes()[:4] == b"\x89PNG"


def test_python_api_returns_the_diagnosis(leak_dataset):
    d = diagnose(leak_dataset.experiment)
    assert d.cause == "leak"
    assert verdict(d).startswith("peaks drift down")
    assert to_json(d)["cause"] == "leak"


def zeroed_copy(experiment: Path, folder: Path) -> Path:
    """`experiment` as a rig logs it before zeroing, its load cell reading 7 N and its transducer
    4 kPa with no air and no load, and the zero run that says so (`[test] zero`)."""
    folder.mkdir()
    toml = experiment.read_text()
    data = experiment.with_name(next(line.split('"')[1] for line in toml.splitlines() if line.startswith("data =")))
    lines = data.read_text().splitlines()
    columns = lines[0].split(",")
    force, pressure = columns.index("force_N"), columns.index("pressure_kPa")

    def offset(line):
        values = line.split(",")
        values[force] = repr(float(values[force]) + 7.0)
        values[pressure] = repr(float(values[pressure]) + 4.0)
        return ",".join(values)

    (folder / data.name).write_text("\n".join([lines[0], *map(offset, lines[1:])]) + "\n")
    zero = ["time_s,elongation_m,force_N,pressure_kPa", *(f"{t},0,{7 + 0.1 * (-1) ** t},4.0" for t in range(10))]
    (folder / "zero.csv").write_text("\n".join(zero) + "\n")
    (folder / "test.toml").write_text(toml.replace(f'data = "{data.name}"', f'data = "{data.name}"\nzero = "zero.csv"'))
    return folder / "test.toml"


ZERO_READ = "its zero run (no air) found the instruments reading force_N 7 N ("


def test_a_zero_run_is_taken_off_and_its_reading_reported(leak_dataset, tmp_path):
    # `[test] zero` takes the zero run's means off, so the diagnosis is the zeroed data's, and the
    # report keeps what the zero run read: the instruments' own offsets, which the zeroed data no
    # longer show. In a campaign, each test's line says what its own zero run read.
    d = diagnose(zeroed_copy(leak_dataset.experiment, tmp_path / "a"))
    assert d.cause == "leak"
    notes = [n for n in to_json(d)["warnings"] if "zeroed" in n]
    assert len(notes) == 1 and notes[0]["offsets"] == pytest.approx({"force_N": 7.0, "gauge_pressure_Pa": 4e3})
    # each offset beside the noise of one sample of its channel, the scale of what it would have done
    over = {c: v / d.problem.sigma[c] for c, v in notes[0]["offsets"].items()}
    assert notes[0]["over_noise"] == pytest.approx(over)
    read = f"force_N 7 N ({over['force_N']:.1f}x its noise), pressure_kPa 4 kPa ({over['gauge_pressure_Pa']:.1f}x"
    assert ZERO_READ in verdict(d) and read in verdict(d)
    # The same test twice, each with its own zero run (a campaign's mechanics, not its evidence).
    c = diagnose([tmp_path / "a" / "test.toml", zeroed_copy(leak_dataset.experiment, tmp_path / "b")])
    assert sum(ZERO_READ in line for line in verdict(c).splitlines()) == 2
    assert all(any("zeroed" in n for n in test["warnings"]) for test in to_json(c)["per_test"])


def test_a_zero_run_holds_the_offsets_it_measured(leak_dataset, tmp_path):
    # The zero run read the load cell and the transducer at nothing and took that off the data: on
    # the zeroed data their offsets are known to be zero. Fitted again, an offset could only take a
    # share of another misfit (the near-model world's load cell, strong seed 9, zeroed of its true
    # -10 N: refitted at -22.8 N beside the membrane's scale at its bound 0). Their other terms, a
    # gain and a nonlinearity, which a zero run cannot read, stay free; and the test the report may
    # ask for is never the zero run the test already has.
    def searched(d, name):
        return set(next(j.fit.params for j in d.candidates if j.fit.name == name))

    plain = diagnose(leak_dataset.experiment)
    zeroed = diagnose(zeroed_copy(leak_dataset.experiment, tmp_path / "a"))
    assert searched(plain, "load_cell") == {"offset_N", "nonlinearity_per_kN"}
    assert searched(plain, "sensor_offset") == {"offset_Pa", "gain"}
    assert searched(zeroed, "load_cell") == {"nonlinearity_per_kN"}
    assert searched(zeroed, "sensor_offset") == {"gain"}
    transducer = next(j.fit for j in zeroed.candidates if j.fit.name == "sensor_offset")
    check = separating_test(zeroed.problem, transducer, zeroed.baseline, "check", (ZERO_RUN,))
    assert check.variant is None and check.tried == {"zero_run": "not run: the test has its zero run"}
    # Fitted on two such tests at once (a campaign's one muscle), the offset stays held.
    other = diagnose(zeroed_copy(leak_dataset.experiment, tmp_path / "b"))
    cells = [next(j.fit for j in d.candidates if j.fit.name == "load_cell") for d in (zeroed, other)]
    joint = calibrate_jointly(
        [zeroed.problem, other.problem], cells, ["a", "b"], effect=("load_cell", lambda: catalog().make("load_cell"))
    )
    assert "nonlinearity_per_kN" in joint.params and "offset_N" not in joint.params


def write(tmp_path, csv_text):
    (tmp_path / "run.csv").write_text(csv_text)
    path = tmp_path / "run.toml"
    path.write_text(
        "[muscle]\nlength_m = 0.225\n[test]\ninflation_pressure_kPa = 200\nambient_temperature_C = 22\n"
        'data = "run.csv"\n'
    )
    return path


def triangle_csv(cycles, columns="time_s,elongation_m,force_N", value="{f}", pressure=None):
    rows = [columns]
    t = 0.0
    for _ in range(cycles):
        for e in list(np.linspace(0, 0.04, 11)) + list(np.linspace(0.04, 0, 11))[1:]:
            f = 100 * e / 0.04
            rows.append(f"{t:.2f},{e:.5f}," + value.format(f=f, p=pressure if pressure is not None else 200 + f))
            t += 0.5
    return "\n".join(rows) + "\n"


def test_too_few_cycles_is_named(tmp_path):
    with pytest.raises(
        ExperimentError,
        match=r"run.csv: column elongation_m: found 3 stretch cycle\(s\); "
        "diagnosis fits on some and holds others out, so it needs at least 4",
    ):
        diagnose(write(tmp_path, triangle_csv(3)))


def test_missing_channels_are_named(tmp_path):
    path = write(tmp_path, triangle_csv(5, columns="time_s,elongation_m", value="").replace(",\n", "\n"))
    with pytest.raises(ExperimentError, match="no measured channel"):
        diagnose(path)


def test_units_that_cannot_be_right_are_named(tmp_path):
    # Pressure written in pascals: row 2 of the file (the first data row), column 4.
    path = write(
        tmp_path,
        triangle_csv(5, columns="time_s,elongation_m,force_N,pressure_kPa", value="{f},{p}", pressure=200000.0),
    )
    with pytest.raises(ExperimentError, match=r"run.csv:2: column 4 \(pressure_kPa\) = 200000 .* pascals"):
        diagnose(path)


def test_cli_reports_bad_input_without_traceback(tmp_path, run_pamkit):
    done = run_pamkit("diagnose", write(tmp_path, triangle_csv(5).replace("0.50,", "nan,", 1)))
    assert done.returncode == 2
    assert "run.csv:3: column 1 (time_s) has no value: every row needs its time" in done.stderr
    assert "Traceback" not in done.stderr


def test_cycles_are_found_through_encoder_noise():
    # 7 triangle cycles of 40 mm with 5 um of noise: 7 cycles, split 4 fitted / 3 held out.
    rng = np.random.default_rng(1)
    e = np.tile(np.concatenate([np.linspace(0, 0.04, 50), np.linspace(0.04, 0, 50)[1:]]), 7)
    cycles = find_cycles(e + rng.normal(0, 5e-6, e.size))
    assert len(cycles) == 7
    fit, held = split_cycles(cycles)
    assert list(fit) == [0, 2, 4, 6] and list(held) == [1, 3, 5]


def test_noise_scale_recovers_white_noise_on_a_curve():
    # sigma = 0.7 on a smooth exponential: the estimate within 10 % (4000 samples: the
    # median's own scatter is ~2 %).
    rng = np.random.default_rng(2)
    t = np.linspace(0, 40, 4000)
    x = 100 * np.exp(np.sin(t / 3)) + rng.normal(0, 0.7, t.size)
    assert noise_scale(x) == pytest.approx(0.7, rel=0.1)


def test_ljung_box_tells_noise_from_structure():
    rng = np.random.default_rng(3)
    noise = rng.normal(size=2000)
    walk = np.cumsum(noise)
    assert ljung_box_p(noise) > 0.01  # white noise: no reason to reject (seeded: p is fixed)
    assert ljung_box_p(walk) < 1e-10  # a random walk is anything but white


def test_programmed_motion_recovers_ramps_holds_and_corners():
    # A bench program: rest, 4 cycles of 20 mm at 5 mm/s with a 3 s hold at the top, sampled at
    # 10 Hz with corners between samples, read through 1 um of encoder noise.
    from pamkit.diagnosis.series.motion import programmed_motion

    knots_t, knots_e, t = [0.0, 1.03], [0.0, 0.0], 1.03
    for _ in range(4):
        knots_t += [t + 4.0, t + 7.0, t + 11.0]
        knots_e += [0.02, 0.02, 0.0]
        t += 11.0
    time = np.arange(0.0, t + 1.0, 0.1)
    truth = np.interp(time, knots_t, knots_e)
    measured = truth + np.random.default_rng(4).normal(0, 1e-6, time.size)
    motion = programmed_motion(time, measured)
    # Every corner (13: the end of the rest, then turning points and hold ends, none on a
    # sample) comes back as a knot within a hundredth of the sample interval...
    for corner in knots_t[1:]:
        assert np.min(np.abs(motion.time_s - corner)) < 1e-3
    # ...and every knot, samples and corners alike, lies on the true motion (1 um of noise
    # averaged over a ramp leaves far less than 1 um).
    assert np.max(np.abs(motion.elongation_m - np.interp(motion.time_s, knots_t, knots_e))) < 1e-6


def test_programmed_motion_keeps_a_curve_as_measured():
    from pamkit.diagnosis.series.motion import programmed_motion

    time = np.linspace(0, 60, 1200)
    curve = 0.02 * (1 - np.cos(2 * np.pi * time / 15))  # not ramps and holds: nothing to fit
    motion = programmed_motion(time, curve)
    np.testing.assert_array_equal(motion.time_s, time)
    np.testing.assert_array_equal(motion.elongation_m, curve)


def test_knots_after_turns_cut_the_first_travel_after_each_turn_and_keep_the_samples():
    from pamkit.diagnosis.series.motion import measured_motion, with_knots_after_turns

    # Rest, up 10 mm in 1 mm steps, a hold, on up 2 mm (no turn: the same direction), down to 0.
    elongation = np.array([0, 0, *range(1, 11), 10, 10, 11, 12, *range(11, -1, -1)], dtype=float) * 1e-3
    motion = measured_motion(np.arange(elongation.size, dtype=float), elongation)
    refined, rows = with_knots_after_turns(motion, 2.5e-3, 4)
    # Every sample is a knot of the refined motion, where the samples now sit...
    np.testing.assert_array_equal(refined.time_s[rows], motion.time_s)
    np.testing.assert_array_equal(refined.elongation_m[rows], motion.elongation_m)
    np.testing.assert_array_equal(refined.sample_rows, rows)
    # ...every new knot lies on the samples' straight lines...
    np.testing.assert_allclose(refined.elongation_m, np.interp(refined.time_s, motion.time_s, elongation), atol=1e-15)
    # ...and the intervals cut in four are the first three after each turn (2.5 mm of travel,
    # 1 mm each): from rest, and at the top; not after the hold, where the motion goes on up.
    cut = np.flatnonzero(np.diff(rows) > 1)
    np.testing.assert_array_equal(cut, [1, 2, 3, 15, 16, 17])
    assert np.all(np.diff(rows)[cut] == 4)


@pytest.mark.parametrize(
    "change, message",
    [
        # Data inconsistent with the declared test: each is an error that says what is inconsistent,
        # never a confident cause with its parameters at their bounds.
        (
            lambda toml, csv: (toml.replace("inflation_pressure_kPa = ", "inflation_pressure_kPa = 1999 #"), csv),
            "inflation_pressure_kPa = 1999, but the data start at",
        ),
        (lambda toml, csv: (toml, _times_in_milliseconds(csv)), "is the time column in milliseconds"),
        (
            lambda toml, csv: (toml.replace("fiber_revolutions = 2", "fiber_revolutions = 20"), csv),
            "past the locking angle 54.7 deg",
        ),
    ],
    ids=["inflation pressure", "milliseconds", "locking angle"],
)
def test_data_that_contradict_the_declared_test_are_named_before_fitting(tmp_path, change, message):
    files = synthesize("none", 21, tmp_path)
    toml, csv = change(files.experiment.read_text(), files.data.read_text())
    files.experiment.write_text(toml)
    files.data.write_text(csv)
    with pytest.raises(ExperimentError, match=message):
        diagnose(files.experiment)


def _times_in_milliseconds(csv: str) -> str:
    lines = csv.splitlines()
    rows = [line.split(",") for line in lines[1:]]
    return "\n".join([lines[0]] + [",".join([f"{float(r[0]) * 1000:g}", *r[1:]]) for r in rows]) + "\n"


def test_the_bundled_supplied_sweep_names_the_slack_its_writer_put_in(thesis_dir):
    # The bundled supplied sweep (tests/independent, isometric_sweep seed 3) has the braid go slack
    # wherever the independent model's static tension is negative: 318 samples of the vented
    # plateaus. The friction scale, free in the baseline, ends below its plausible range, but its
    # interval reaches into it: the data leave it free, so it is held against no cause.
    d = diagnose(thesis_dir.parent / "supplied" / "isometric_sweep.toml", threads=2)
    assert [c.label for c in d.decision.causes] == ["braid_slack"]
    text = verdict(d)
    assert text.startswith("force stays at zero where the model pushes: braid_slack;")
    assert "braid_slack, ;" not in text and "nothing is left above the noise" in text


def test_a_gain_its_held_out_units_do_not_all_bear_out_is_shown(tmp_path):
    # An out-of-catalog cause (tests/independent's Mullins softening, seed 3): a shift of the force
    # channel gains on the whole and the BIC falls, but its interval over the held-out cycles holds
    # zero. The verdict says what it looks like and why it is no cause, not that nothing gains.
    d = diagnose(mullins(3, tmp_path).experiment, threads=2)
    best = d.candidates[0]
    assert not best.significant and best.score.combined_gain >= 0.03 and best.score.combined_ci95[0] <= 0.0
    text = verdict(d)
    assert text.startswith("unexplained") and "it looks like" in text and f"{best.fit.name} gains" in text
    assert "holds zero" in text and "no catalog effect gains" not in text


def test_an_unexplained_figure_draws_what_the_data_look_like(leak_dataset):
    # Where nothing is named, the verdict says what the best refused fit looks like; the figure
    # draws what that fit leaves, dashed, beside what the baseline leaves. (The decision is made
    # here by hand: this checks the drawing, not what is refused.)
    d = diagnose(leak_dataset.experiment, threads=2)
    refused = d.candidates[0]
    d = replace(d, decision=replace(d.decision, cause="unexplained", causes=[], rejected=refused), extended=d.baseline)
    residuals = next(axis for axis in series_figure(d, "unexplained").axes if axis.get_title() == "residuals")
    (looks,) = [line for line in residuals.get_lines() if line.get_label().startswith("looks like")]
    assert looks.get_label() == f"looks like ({refused.fit.name}), not named" and looks.get_linestyle() == "--"
    channel = d.problem.channels[0]
    left = value_from_si(channel, d.problem.measured[channel]) - value_from_si(channel, refused.fit.predicted[channel])
    assert np.allclose(looks.get_ydata(), left)
