"""A campaign of time series: several bench tests of one muscle (docs/diagnosis.md, "campaigns").

Each test is diagnosed alone first (its baseline calibrated on its own cycles: the inflation
pressure, friction and bladder scales are per-test nuisances). A cause must then hold across the
campaign, held out by whole test: for each test, the effect's parameters are the median of what
the *other* tests fitted, the test's baseline as calibrated beside the effect (its own candidate
fit, on its fitted cycles) carries them, and the gain is scored on its held-out cycles exactly as
a candidate's is (score.score, credited channels). The baseline calibrated without the effect
would not do: it has absorbed what it could of the effect (a dead volume, in a braid wound
tighter), and the effect added to it counts twice. What is carried: every cause a test named, both
candidates of a tie a test could not break, a named cause's close rival (the test its diagnosis
named to break the tie or confirm the cause, run and diagnosed beside it, is such a campaign), and
a candidate refused only because one that cannot be named explains more (decide.outdone: a dead
volume outdone in both of two inflations by a viscoelastic bladder at its slowest time constant,
where compliant fibres, named in one, were carried alone). The campaign names the cause whose
leave-one-test-out gain is significant in every test (at least MIN_GAIN, its 95 % interval above
zero) and above every other such cause's in every test (their intervals apart); `none` when every
test says `none`; otherwise `unexplained`, saying where the cause fails to carry, which causes it
does not tell apart, or where the tests disagree.

Beside the per-test calibrations, one muscle is calibrated on all the tests at once (joint.py):
its shared values and their intervals are the campaign's baseline, and a test the shared muscle
fits much worse than its own calibration is reported.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from pamkit.diagnosis.coordinates import Finding, findings
from pamkit.diagnosis.series.calibrate import Fit, one_blas_thread
from pamkit.diagnosis.series.joint import DISAGREES, JointFit, calibrate_jointly
from pamkit.diagnosis.series.result import Diagnosis
from pamkit.diagnosis.series.score import score
from pamkit.diagnosis.significance import MIN_GAIN
from pamkit.io.experiment import test_names
from pamkit.plots import pyplot, save_figure

# Fewer tests than this cannot hold a test out and still fit the effect on the others.
MIN_TESTS = 2


@dataclass
class Transfer:
    """An effect carried to one test with the parameters the other tests fitted."""

    test: str
    params: dict[str, float]  # the median of the other tests' fits
    gain: float  # credited held-out gain on this test's held-out cycles
    gain_ci95: list[float]
    carries: bool  # gain >= MIN_GAIN with its interval above zero


@dataclass
class SeriesCampaign:
    paths: list[str]
    tests: list[str]  # a short name for each (pamkit.io.experiment.test_names)
    diagnoses: list[Diagnosis]
    transfers: dict[str, list[Transfer]]  # per effect some test named or tied on: one per test
    cause: str
    reason: str
    joint: JointFit  # one muscle calibrated on every test
    extended: JointFit | None  # with the cause, its parameters shared too
    warnings: list[Finding]  # the shared values at a bound or outside their plausible ranges


def _single_effect_fits(d: Diagnosis) -> dict[str, Fit]:
    """Each single-effect candidate a test fitted, by its label (`sensor_lag:channel=force_N`)."""
    return {j.fit.name: j.fit for j in d.candidates if len(j.fit.effects) == 1 and j.fit.error is None}


def _carry(catalog, label: str, held: Diagnosis, own: Fit, others: list[Fit], name: str, seed: int) -> Transfer:
    """`label` carried to the test `held` with the median parameters of `others` (the other tests'
    fits), on the baseline `own` (the test's fit of the effect) calibrated beside it."""
    effect = catalog.parse(label)
    numeric = {p.name for p in effect.parameters()}.intersection(*(fit.params for fit in others))
    params = {key: float(np.median([fit.params[key] for fit in others])) for key in sorted(numeric)}
    for key, value in params.items():
        effect.set(key, value)
    problem, baseline = held.problem, held.baseline
    predicted = problem.predictor.predict(own.baseline_x, [effect])
    carried = Fit(
        label,
        [effect],
        own.baseline_x,
        params,
        predicted,
        problem.chi2_by_channel(predicted),
        baseline.parameter_count,  # nothing fitted on this test beyond its own baseline
    )
    s = score(problem, baseline, carried, np.random.default_rng(seed))
    carries = s.credited_gain >= MIN_GAIN and s.credited_ci95[0] > 0.0
    return Transfer(name, params, float(s.credited_gain), [float(v) for v in s.credited_ci95], carries)


def _overlaps(lead: list[Transfer], other: list[Transfer]) -> list[str]:
    """The tests where `lead`'s held-out gain is not above `other`'s, their 95 % intervals meeting."""
    return [x.test for x, y in zip(lead, other) if x.gain_ci95[0] <= y.gain_ci95[1]]


def _above(lead: list[Transfer], other: list[Transfer]) -> bool:
    """Whether `lead` gains above `other` in every test, their 95 % intervals apart."""
    return not _overlaps(lead, other)


def campaign_of_series(diagnoses: list[Diagnosis], catalog, progress=None, threads: int = 2) -> SeriesCampaign:
    """Calibrates one muscle on every test, carries every effect some test named (or could not
    tell from another) to each test from the others, and decides."""
    with one_blas_thread():
        return _campaign_of_series(diagnoses, catalog, progress or (lambda message: None), threads)


def _campaign_of_series(diagnoses: list[Diagnosis], catalog, progress, threads: int) -> SeriesCampaign:
    paths = [str(d.problem.experiment.path) for d in diagnoses]
    names = test_names([d.problem.experiment for d in diagnoses])
    progress(f"calibrating one muscle on all {len(diagnoses)} tests")
    joint = calibrate_jointly([d.problem for d in diagnoses], [d.baseline for d in diagnoses], names, threads)
    fits = [_single_effect_fits(d) for d in diagnoses]
    # Beside the causes named, the two of a tie, a cause's close rival and, where a test leaves
    # structure, a candidate refused only because one that cannot be named explains more: what a
    # test could not tell apart firmly, another test may. A test within its noise has no structure
    # for such a candidate to be a part of (two inflations of a weak dead volume, each `none`:
    # compliant fibres outdone there carried to both by 0.07 and 0.18 and were named).
    named = (
        {cause.label for d in diagnoses for cause in d.decision.causes}
        | {
            label
            for d in diagnoses
            if d.separation is not None and d.separation.purpose != "check"
            for label in d.separation.between
        }
        | {j.fit.name for d in diagnoses if d.cause != "none" for j in d.candidates if j.significant and j.only_outdone}
    )
    transfers: dict[str, list[Transfer]] = {}
    for label in sorted(named):
        if not all(label in f for f in fits):
            continue  # an effect one test could not fit cannot be carried to it
        progress(f"carrying {label} to each test from the others")
        transfers[label] = [
            _carry(
                catalog,
                label,
                d,
                fits[k][label],
                [fits[j][label] for j in range(len(diagnoses)) if j != k],
                names[k],
                seed=k,
            )
            for k, d in enumerate(diagnoses)
        ]
    holding = {label: t for label, t in transfers.items() if all(x.carries for x in t)}
    leader = max(holding, key=lambda label: float(np.mean([x.gain for x in holding[label]])), default=None)
    alike = [label for label in holding if label != leader and not _above(holding[leader], holding[label])]
    if leader is not None and not alike:
        cause = leader
        worst = min(x.gain for x in holding[cause])
        reason = f"its parameters from the other tests gain on every test's held-out cycles (the least {worst:.2f})"
        others = [label for label in holding if label != leader]
        if others:
            reason += f", above {', '.join(others)} in every test"
    elif leader is not None:
        cause = "unexplained"
        overlapping = [f"{label} in {', '.join(_overlaps(holding[leader], holding[label]))}" for label in alike]
        reason = (
            f"{leader} carries to every test, and so does {', '.join(alike)}, their held-out gains' intervals "
            f"overlapping ({'; '.join(overlapping)}): the campaign does not tell them apart"
        )
    elif all(d.cause == "none" for d in diagnoses):
        cause, reason = "none", "every test's calibrated model explains it within its noise"
    else:
        cause = "unexplained"
        said = ", ".join(f"{n}: {d.cause}" for n, d in zip(names, diagnoses))
        failing = [
            f"{label} does not carry to {', '.join(x.test for x in t if not x.carries)}"
            for label, t in transfers.items()
        ]
        reason = f"no cause holds across the campaign ({said})" + (f"; {'; '.join(failing)}" if failing else "")
    extended = None
    if cause in holding:
        progress(f"calibrating one muscle with {cause} on all {len(diagnoses)} tests")
        extended = calibrate_jointly(
            [d.problem for d in diagnoses],
            [f[cause] for f in fits],
            names,
            threads,
            effect=(cause, lambda label=cause: catalog.parse(label)),
        )
        shared_baseline = set(joint.params)
        implausible = [f for f in findings(extended) if f.parameter not in shared_baseline]
        if implausible:  # a cause is never named with a parameter at a bound or implausible
            reason = (
                f"{cause} carries to every test, but fitted on all of them at once "
                f"{'; '.join(f.sentence() for f in implausible)}"
            )
            cause = "unexplained"
    warnings = findings(joint) + (findings(extended) if extended else [])
    return SeriesCampaign(paths, names, diagnoses, transfers, cause, reason, joint, extended, warnings)


def _joint_json(j: JointFit) -> dict:
    return {
        "params": j.params,
        "intervals": {k: list(v) for k, v in j.intervals.items()},
        "undetermined": {name: {"trades_against": partners} for name, partners in j.undetermined.items()},
        "per_test": [
            {
                "test": s.test,
                "params": s.own,
                "rmse_ratio": s.rmse_ratio,
                "carried_rmse_ratio": s.carried_ratio,
                "alone": s.alone,
                "disagrees": s.disagrees,
            }
            for s in j.shares
        ],
    }


def _shared(j: JointFit) -> str:
    return ", ".join(
        f"{name} = {value:.4g} (not determined by the data)"
        if name in j.undetermined
        else f"{name} = {value:.4g} [{j.intervals[name][0]:.4g}, {j.intervals[name][1]:.4g}]"
        for name, value in j.params.items()
    )


def to_json(c: SeriesCampaign, test_report) -> dict:
    """The campaign's report: its verdict, each effect carried test by test, and each test's own
    report (`test_report`, pamkit.diagnosis.report.to_json)."""
    return {
        "kind": "campaign",
        "verdict": verdict(c),
        "tests": c.paths,
        "held_out": "test",
        "cause": c.cause,
        "reason": c.reason,
        "baseline": _joint_json(c.joint),
        "extended": ({"effects": [c.extended.effect], **_joint_json(c.extended)} if c.extended else None),
        # The cause carried to every test, with its gain on each; what each test leaves is its own
        # report's remainder (per_test[].remainder).
        "causes": (
            [
                {
                    "effect": c.cause,
                    "params": {k: v for k, v in c.extended.params.items() if k in c.transfers[c.cause][0].params},
                    "gain_by_test": {x.test: x.gain for x in c.transfers[c.cause]},
                    "gain_ci95_by_test": {x.test: x.gain_ci95 for x in c.transfers[c.cause]},
                }
            ]
            if c.extended is not None and c.cause in c.transfers
            else []
        ),
        "warnings": [f.to_json() for f in c.warnings],
        "carried": {
            label: [
                {"test": x.test, "params": x.params, "gain": x.gain, "gain_ci95": x.gain_ci95, "carries": x.carries}
                for x in t
            ]
            for label, t in c.transfers.items()
        },
        "per_test": [test_report(d) for d in c.diagnoses],
    }


def verdict(c: SeriesCampaign) -> str:
    lines = [f"campaign of {len(c.tests)} tests, each held out in turn: cause {c.cause} — {c.reason}"]
    lines.append(f"  one muscle calibrated on every test: {_shared(c.joint)}")
    if c.extended:
        lines.append(f"  with {c.extended.effect}, shared by every test: {_shared(c.extended)}")
    final = c.extended or c.joint
    ratios = ", ".join(f"{s.test} {s.carried_ratio:.2f}" for s in final.shares)
    lines.append(
        f"  that muscle fitted without each test predicts its held-out units at {ratios} times the error of "
        "the test's own fit"
    )
    lines += [f"  the shared muscle {f.sentence()}" for f in c.warnings]
    for s in (c.extended or c.joint).shares:
        if s.disagrees:
            alone = ", ".join(f"{k} = {v:.3g}" for k, v in s.alone.items())
            lines.append(
                f"  {s.test} disagrees: the shared muscle fits it {s.rmse_ratio:.1f}x worse than its own fit "
                f"({alone}): a structural misfit, not one muscle's parameters"
            )
    for name, d in zip(c.tests, c.diagnoses):
        s = d.separation
        told = f"; to tell them apart: {s.test_phrase()}" if s is not None and s.separates else ""
        done_to_data = d.data_clause
        if s is None or s.purpose == "check":
            lines.append(f"  {name}: alone, {d.cause}{done_to_data}")
        elif s.purpose == "tie":
            lines.append(f"  {name}: alone, {d.cause} ({' and '.join(s.between)} tied{told}){done_to_data}")
        else:
            lines.append(f"  {name}: alone, {d.cause} ({s.between[1]} close behind{told}){done_to_data}")
    for label, t in c.transfers.items():
        gains = ", ".join(f"{x.test} {x.gain:.2f} [{x.gain_ci95[0]:.2f}, {x.gain_ci95[1]:.2f}]" for x in t)
        lines.append(f"  {label} from the other tests: held-out gain {gains}")
    return "\n".join(lines)


def plot(c: SeriesCampaign, path: str | Path) -> Path:
    """Writes `figure(c)` to `path` (PNG or PDF by its suffix)."""
    return save_figure(figure(c), path)


def figure(c: SeriesCampaign):
    """Three panels, test by test: each effect some test named, carried to the test from the
    others (held-out gain with its 95 % interval, against MIN_GAIN); how the one shared muscle
    fits the test against its own fit (fitted units, and held-out units with the muscle fitted
    without the test, against DISAGREES); and each shared value as the test fitted it alone,
    relative to the shared value and its interval. A matplotlib Figure, open in pyplot."""
    plt = pyplot()

    figure, (carried, shared, values) = plt.subplots(3, 1, figsize=(7.5, 9.6))
    positions = np.arange(len(c.tests))
    labels = list(c.transfers)
    width = 0.8 / max(len(labels), 1)
    for i, label in enumerate(labels):
        gains = np.array([x.gain for x in c.transfers[label]])
        low = gains - np.array([x.gain_ci95[0] for x in c.transfers[label]])
        high = np.array([x.gain_ci95[1] for x in c.transfers[label]]) - gains
        carried.bar(positions + i * width, gains, width, yerr=[low, high], capsize=3, label=label)
    carried.axhline(MIN_GAIN, color="k", lw=0.8, ls=":", label=f"MIN_GAIN {MIN_GAIN}")
    if not labels:
        carried.text(0.5, 0.5, "no test named a cause its own", ha="center", va="center", transform=carried.transAxes)
    carried.set_xticks(positions + (0.4 - width / 2 if labels else 0.0), c.tests)
    carried.set_ylabel("held-out gain,\nparameters from the other tests")
    carried.set_title(f"campaign: cause {c.cause}", fontsize=9)
    carried.legend(fontsize=7)

    joint = c.extended or c.joint
    model = f"the shared muscle{f' with {c.extended.effect}' if c.extended else ''}"
    shared.bar(positions - 0.2, [s.rmse_ratio for s in joint.shares], 0.4, label="fitted units, all tests")
    shared.bar(positions + 0.2, [s.carried_ratio for s in joint.shares], 0.4, label="held-out units, fitted without it")
    shared.axhline(1.0, color="k", lw=0.8)
    shared.axhline(DISAGREES, color="C3", lw=0.8, ls=":", label=f"disagrees above {DISAGREES:g}")
    shared.set_xticks(positions, c.tests)
    shared.set_ylabel(f"RMSE of {model}\n/ the test's own fit")
    shared.legend(fontsize=7)

    names = list(joint.params)
    step = 0.8 / max(len(names), 1)
    for i, name in enumerate(names):
        value = joint.params[name]
        if value == 0.0:
            continue
        low, high = joint.intervals[name]
        x = positions - 0.4 + (i + 0.5) * step
        band = [[1.0 - low / value] * len(x), [high / value - 1.0] * len(x)]
        values.errorbar(x, np.ones(len(x)), yerr=band, fmt="none", color=f"C{i}", alpha=0.4, lw=6)
        values.plot(x, [s.alone[name] / value for s in joint.shares], "o", color=f"C{i}", label=name)
    values.axhline(1.0, color="k", lw=0.8)
    values.set_xticks(positions, c.tests)
    values.set_ylabel("each test alone / shared value\n(bar: the shared 95 % interval)")
    values.legend(fontsize=7)
    for axis in (carried, shared, values):
        axis.grid(alpha=0.3, axis="y")
    figure.tight_layout()
    return figure
