"""Diagnosis, the orchestration of its stages: find the test's units (kinds), calibrate the
baseline on some of them (calibrate), fit every candidate effect on the same units
(candidates), score all of them on the units held out and decide (decide), look for what the
catalog lacks in what remains (discover), and report (report)."""

from __future__ import annotations

import hashlib
import math
import os
import time as clock
import warnings as python_warnings
from dataclasses import replace
from pathlib import Path

import numpy as np

from pamkit._core import EffectCatalog, EffectStage, GasMode
from pamkit.diagnosis.discover import DiscoveryError, discover, feature_library
from pamkit.diagnosis.series.calibrate import Fit, fit_baseline, one_blas_thread, thread_pool
from pamkit.diagnosis.series.campaign import MIN_TESTS, campaign_of_series
from pamkit.diagnosis.series.candidates import SCREEN_DROP, candidates, fit_candidate
from pamkit.diagnosis.series.causes import add_cause, reads_explained, rival_beside_a_second
from pamkit.diagnosis.series.decide import PAIR_TRIGGER, Decision, Judgement, decide, judge
from pamkit.diagnosis.series.declared import declared_build, told_from_the_build
from pamkit.diagnosis.series.findings import baseline_findings
from pamkit.diagnosis.series.glitches import GlitchWarning, without_glitches
from pamkit.diagnosis.series.instruments import noise_ratios, reads_off, structured
from pamkit.diagnosis.series.joint import check_one_muscle
from pamkit.diagnosis.series.kinds import Problem, build_problem
from pamkit.diagnosis.series.refused import outdone_beside_a_second, tie_beside_a_second
from pamkit.diagnosis.series.result import Diagnosis
from pamkit.diagnosis.series.score import score
from pamkit.diagnosis.series.separate import VARIANTS, ZERO_RUN, separating_test
from pamkit.diagnosis.significance import MIN_GAIN
from pamkit.diagnosis.tables.engine import TableDiagnosis, diagnose_table
from pamkit.effects import catalog as builtin_catalog
from pamkit.io.columns import COLUMN_UNITS, OPTIONAL_COLUMNS, difference_from_si, file_name, file_unit
from pamkit.io.experiment import Experiment, load_tests
from pamkit.io.guards import ExperimentError

__all__ = ["MIN_GAIN", "MAX_DIAGNOSED_ROWS", "ThinningWarning", "diagnose", "data_seed"]

REFIT_LEADERS = 3  # leading measurement candidates refitted with the baseline free
# A time series longer than this is diagnosed on every k-th row (the fewest k that fits), as if
# logged at 1/k of its rate: each model run costs about 1 us per row, and a diagnosis makes
# several hundred, so 10^6 rows (a 17-minute test at 1 kHz) took 400 s; at 10^5 rows it is
# about ten times less. The rows kept are samples as measured (not means), so the noise and
# everything diagnosis knows of a channel is that of the slower test, the kind of test
# (10-100 Hz) the synthetic benchmarks validate it on.
MAX_DIAGNOSED_ROWS = 100_000


class ThinningWarning(UserWarning):
    """A long test is diagnosed on every k-th row; the message says how many were kept."""


def thinned(experiment: Experiment, max_rows: int | None = None) -> tuple[Experiment, dict | None]:
    """The experiment with every k-th row (the fewest k that leaves at most `max_rows`, by
    default MAX_DIAGNOSED_ROWS), and a note of it for the report's warnings (None when every
    row is kept)."""
    max_rows = MAX_DIAGNOSED_ROWS if max_rows is None else max_rows
    rows = experiment.time_s.size
    if rows <= max_rows:
        return experiment, None
    step = math.ceil(rows / max_rows)
    kept = replace(experiment, columns={name: values[::step].copy() for name, values in experiment.columns.items()})
    interval = float(np.median(np.diff(experiment.time_s)))
    message = (
        f"{experiment.data_path}: {rows} rows, more than the {max_rows} a diagnosis runs on: diagnosed on one row "
        f"in {step} ({kept.time_s.size} rows, one every {step * interval:.3g} s instead of {interval:.3g} s)"
    )
    note = {"thinned": message, "step": step, "rows_read": rows, "rows_diagnosed": int(kept.time_s.size)}
    return kept, note


def zeroed(experiment: Experiment, sigma: dict[str, float]) -> dict | None:
    """What the test's zero run (`[test] zero`) took off its channels, as a note for the report's
    warnings and its sentence (None without one): the instruments' own reading with no air and no
    load, which the zeroed data no longer show (a transducer reading 5 kPa there has that offset),
    each over the noise of one sample of its channel (`sigma`, where the channel is compared)."""
    if not experiment.zeroed:
        return None
    over = {c: abs(v) / sigma[c] for c, v in experiment.zeroed.items() if sigma.get(c, 0.0) > 0.0}
    read = ", ".join(
        f"{file_name(c)} {difference_from_si(c, v):.3g} {file_unit(c) or COLUMN_UNITS.get(c, '')}"
        + (f" ({over[c]:.1f}x its noise)" if c in over else "")
        for c, v in experiment.zeroed.items()
    )
    return {
        "zeroed": f"its zero run (no air) found the instruments reading {read} at nothing, taken off the data first",
        "offsets": dict(experiment.zeroed),
        "over_noise": over,
    }


def data_seed(problem: Problem) -> int:
    """A seed for the bootstrap drawn from the data itself: the same input gives the same
    report on any machine and thread count."""
    digest = hashlib.sha256()
    for name in ["time_s", *problem.channels]:
        values = problem.experiment.time_s if name == "time_s" else problem.measured[name]
        digest.update(np.ascontiguousarray(values, dtype="<f8").tobytes())
    return int.from_bytes(digest.digest()[:8], "little")


def _better(refit: Judgement, fit: Judgement) -> bool:
    """Whether a measurement effect's refit with the baseline free replaces its fit on the
    calibrated baseline: when it explains more, unless it is the refit alone that cannot be named
    (the baseline moved to a bound: an offset trading against the inflation pressure)."""
    if fit.significant and fit.credible and not refit.credible:
        return False
    return refit.score.combined_gain > fit.score.combined_gain


def discover_remainder(problem: Problem, fit: Fit, seed: int) -> dict:
    """Sparse regression of what `fit` leaves in the channel furthest above its noise, on the
    physical feature library (discover.py): what the catalog lacks, as an equation."""
    ratios = noise_ratios(problem, fit)
    channel = max(problem.channels, key=lambda c: ratios[c])
    experiment = problem.experiment
    # The model's own channels where the data has none (a sealed test logged without pressure).
    simulated = (
        problem.predictor.select(problem.predictor.measurement(fit.baseline_x, fit.effects))
        if set(problem.channels) != set(OPTIONAL_COLUMNS)
        else {}
    )
    simulated = {**simulated, **fit.predicted}

    def column(name):
        return experiment.columns[name] if name in experiment.columns else simulated.get(name)

    try:
        features = feature_library(
            experiment.time_s,
            experiment.elongation_m,
            gauge_pressure_Pa=column("gauge_pressure_Pa"),
            temperature_K=column("temperature_K"),
            ambient_K=experiment.gas_params.ambient_temperature_K if "temperature_K" in experiment.columns else None,
            cycle=problem.cycle.astype(float),
            force_N=fit.predicted.get("force_N"),
        )
        residual = problem.measured[channel] - fit.predicted[channel]
        return discover(
            features,
            residual,
            problem.sigma[channel],
            problem.fit_mask,
            problem.held_mask,
            problem.half_cycle,
            channel,
            COLUMN_UNITS[channel],
            seed=seed % 2**32,
        )
    except DiscoveryError as error:
        return {"channel": channel, "terms": [], "error": str(error)}


def _judged(problem, baseline: Fit, fit: Fit, factory, seed: int) -> Judgement:
    """A candidate's fit judged against the calibrated baseline. Every candidate's bootstrap draws
    the same units: scores differ by the fits alone. One left after its screening step
    (candidates.SCREEN_DROP) that is significant even so is fitted through; one that is not says
    that it was screened, with the step's drop."""
    judged = judge(problem, fit, score(problem, baseline, fit, np.random.default_rng(seed)), baseline)
    if fit.screened is None:
        return judged
    if judged.significant:
        return _judged(problem, baseline, fit_candidate(problem, baseline, factory, fit.name), factory, seed)
    judged.objections.append(
        f"not fitted beyond one Gauss-Newton step from its scan: that step lowers the fitted chi-square by "
        f"{100 * fit.screened:.2g} % (a fit is carried through from {100 * SCREEN_DROP:.0f} %)"
    )
    return judged


def _fit_and_judge(problem, baseline: Fit, factory, label: str, seed: int) -> Judgement | str:
    """A candidate fitted and judged (on a pool's thread), or why its fit failed."""
    fit = fit_candidate(problem, baseline, factory, label, screen=True)
    return _judged(problem, baseline, fit, factory, seed) if fit.error is None else f"fit failed: {fit.error}"


def _refit(problem, baseline: Fit, factory, judged: Judgement, seed: int) -> Judgement:
    """A measurement candidate refitted with the baseline free from its fit on the calibrated
    baseline: the refit where it is better (_better), else the fit as it was."""
    fit = fit_candidate(problem, baseline, factory, judged.fit.name, judged.fit, screen=True)
    if fit is judged.fit or fit.error is not None:
        return judged
    refit = judge(problem, fit, score(problem, baseline, fit, np.random.default_rng(seed)), baseline)
    return refit if _better(refit, judged) else judged


def _ranked(judged: list[Judgement]) -> list[Judgement]:
    return sorted(judged, key=lambda j: (-j.score.combined_gain, j.score.delta_bic, j.fit.name))


def _fit_candidates(problem, baseline: Fit, todo, seed: int, threads, report) -> tuple[list[Judgement], dict]:
    """Every candidate fitted and judged on the calibrated baseline, best first, with the leading
    measurement candidates refitted with the baseline free; and the candidates whose fit failed,
    with why. The baseline's calibration absorbed part of a measurement effect (an offset pulls the
    inflation pressure to its bound), hence the refits. They lead among the measurement effects, not
    among all: an instrument error on one channel (a pressure offset) must not lose its refit
    because another channel's (the load cell's) scored higher on the calibrated baseline. So the
    refits wait only for the measurement candidates, and run while the physics candidates' longer
    fits do: what each fit returns is the same in whatever order the pool runs them."""
    is_measurement = {label: factory().stage() == EffectStage.measurement for label, factory in todo}
    # The physics fits queued first: they take the longest, the measurement fits fill beside them.
    order = sorted(todo, key=lambda item: is_measurement[item[0]])
    results: dict[str, Judgement | str] = {}
    with thread_pool(threads) as pool:
        futures = {
            label: pool.submit(_fit_and_judge, problem, baseline, factory, label, seed) for label, factory in order
        }
        factories = dict(todo)

        def collect(label: str) -> None:
            results[label] = outcome = futures[label].result()
            note = (
                outcome
                if isinstance(outcome, str)
                else f"held-out gain {outcome.score.combined_gain:+.3f}"
                + (" (one step: not fitted further)" if outcome.fit.screened is not None else "")
            )
            report(f"[{len(results)}/{len(todo)}] {label}: {note}")

        for label in (label for label, _ in todo if is_measurement[label]):
            collect(label)
        measured = _ranked([j for label, j in results.items() if not isinstance(j, str)])
        leaders = measured[:REFIT_LEADERS]
        if leaders:
            report(f"refitting {', '.join(j.fit.name for j in leaders)} with the baseline")
        refits = {j.fit.name: pool.submit(_refit, problem, baseline, factories[j.fit.name], j, seed) for j in leaders}
        for label in (label for label, _ in todo if not is_measurement[label]):
            collect(label)
        for label, future in refits.items():
            results[label] = future.result()
    judged = [results[label] for label, _ in todo if not isinstance(results[label], str)]
    failed = {label: results[label] for label, _ in todo if isinstance(results[label], str)}
    return _ranked(judged), failed


def _decided(problem, baseline: Fit, judged: list[Judgement], factories, seed: int, threads, report) -> Decision:
    """The decision on the judged candidates (decide): a tie told apart beside a second cause
    (tie_beside_a_second), or the lead with a second cause where it leaves structure, or its rival
    with one in its place; the instruments among the causes checked (reads_explained); with no
    cause, the lead but for what outdoes it, beside a second (outdone_beside_a_second)."""
    decision = decide(problem, baseline, judged)
    untied = tie_beside_a_second(problem, baseline, decision, judged, factories, seed, threads, report)
    if untied is not None:
        return untied
    while decision.causes:
        if structured(problem, decision.named.fit, PAIR_TRIGGER):
            decision = add_cause(problem, baseline, decision, judged, factories, seed, threads, report)
        else:
            decision = rival_beside_a_second(problem, baseline, decision, judged, factories, seed, report)
        checked = reads_explained(problem, baseline, decision)
        if checked.causes:
            return checked
        # The lead refused carries its objection now, and another candidate may still be a cause.
        # Each pass refuses one more lead, so the loop ends.
        decision = decide(problem, baseline, judged)
    lifted = outdone_beside_a_second(problem, baseline, decision, judged, factories, seed, threads, report)
    return lifted if lifted is not None else decision


def diagnose(
    experiment: Experiment | str | Path | list,
    effect_catalog: EffectCatalog | None = None,
    progress=None,
    threads: int | None = None,
    seed: int | None = None,
) -> Diagnosis | TableDiagnosis:
    """Diagnoses one experiment, or a campaign (a list) of tests of one muscle, or a campaign
    TOML (`[campaign] tests = [...]`). `progress(message)` is called as work proceeds; `seed`
    (by default drawn from the data) seeds the bootstrap. Static tables (isometric maps,
    isotonic and free-inflation tables) are diagnosed by tables/, on held-out lengths, sweeps
    or rows; a campaign of time series by series/campaign.py, each test held out in turn.

    Raises:
        ExperimentError: for data that cannot be diagnosed, naming file, row and column.
    """
    with one_blas_thread():  # the parallelism is the simulations' (calibrate.one_blas_thread)
        return _diagnose(experiment, effect_catalog, progress, threads, seed)


def _diagnose(experiment, effect_catalog, progress, threads, seed) -> Diagnosis | TableDiagnosis:
    started = clock.perf_counter()
    report = progress or (lambda message: None)
    tests = list(experiment) if isinstance(experiment, (list, tuple)) else [experiment]
    loaded = []
    for test in tests:
        if isinstance(test, Experiment):
            loaded.append(test)
            continue
        report(f"reading {test}")
        for one in load_tests(test):
            rows = len(next(iter(one.columns.values())))
            report(f"read {rows} rows of {one.data_path.name} ({clock.perf_counter() - started:.1f} s)")
            loaded.append(one)
    tests = loaded
    effect_catalog = effect_catalog if effect_catalog is not None else builtin_catalog()
    # Tables, alone or with supplied cyclic tests of the same muscle: one muscle calibrated across
    # its characterisations (tables/ samples a supplied series as rows along its path).
    if any(e.is_table for e in tests) and all(e.is_table or e.gas == GasMode.supplied for e in tests):
        return diagnose_table(tests, effect_catalog, progress=progress, threads=threads)
    if len(tests) > 1:
        return _diagnose_series_campaign(tests, effect_catalog, progress, threads, seed)
    experiment, note = thinned(tests[0])
    if note:  # on stderr even with no progress shown (the command line prints warnings as one line)
        python_warnings.warn(note["thinned"], ThinningWarning, 2)
    # Searched in the rows diagnosed: a glitch in a row thinning left out is no glitch of theirs.
    experiment, glitches = (experiment, None) if experiment.keep_glitches else without_glitches(experiment)
    if glitches:  # on stderr too, as a thinned test's
        python_warnings.warn(f"{experiment.data_path}: {glitches['glitches']}", GlitchWarning, 2)
    report("finding the test's cycles and noise")
    problem = build_problem(experiment)
    notes = [n for n in (glitches, note, zeroed(experiment, problem.sigma)) if n]
    notes += [{"reading": sentence} for sentence in experiment.data_warnings]  # what reading the data repaired
    seed = data_seed(problem) if seed is None else seed
    seconds = {"data": clock.perf_counter() - started}  # reading, thinning, finding the units

    report(
        f"calibrating the baseline on {len(np.unique(problem.cycle[problem.fit_mask]))} {problem.unit_name}s "
        f"({', '.join(problem.channels)})"
    )
    phase = clock.perf_counter()
    baseline = fit_baseline(problem)
    seconds["baseline"] = clock.perf_counter() - phase
    report(f"baseline calibrated in {baseline.evaluations} model runs ({seconds['baseline']:.1f} s)")

    skipped = {}
    for name in effect_catalog.names():
        acts, why_not = effect_catalog.make(name).acts_in(problem.predictor.mode)
        if not acts:
            skipped[name] = why_not
    todo = candidates(effect_catalog, problem)
    phase = clock.perf_counter()
    report(f"fitting {len(todo)} candidate effects, {threads or os.cpu_count() or 1} at a time")
    judged, failed = _fit_candidates(problem, baseline, todo, seed, threads, report)
    skipped.update(failed)
    factories = dict(todo)
    seconds["candidates"] = clock.perf_counter() - phase

    report("deciding on held-out units")
    decision = _decided(problem, baseline, judged, factories, seed, threads, report)
    phase = clock.perf_counter()
    declared = declared_build(problem, baseline, decision, seed, report)
    if declared is not None:
        seconds["declared"] = clock.perf_counter() - phase
        decision = told_from_the_build(problem, baseline, decision, declared)
    named = decision.named
    extended = named.fit if named is not None else baseline
    # The base model's strain and the rejected best candidate's findings (why it is not a cause).
    warnings = baseline_findings(baseline)
    if decision.rejected is not None:
        warnings += [
            replace(f, parameter=f"{decision.rejected.fit.name}: {f.parameter}") for f in decision.rejected.findings
        ]
    separation = None
    tied = decision.rejected
    lead = decision.causes[0].judgement if decision.causes else None
    # An instrument's error refused only as not needed (its channel within the noise without it, or
    # a load cell gaining too little to be told from another misfit): the data neither need it nor
    # rule it out, and a test may.
    unneeded_only = (
        tied is not None and tied.unneeded and not (tied.findings or tied.objections or tied.below_resolution)
    )
    # An instrument's error refused on its values (one at a bound or implausible, a share of another
    # misfit taken): this test cannot tell what the instrument reads at nothing from what the muscle
    # does, and a zero run reads it there, whatever the muscle.
    misread = (
        tied is not None
        and not problem.experiment.zeroed
        and not unneeded_only
        and tied.tied_with is None
        and all(reads_off(problem, e) for e in tied.fit.effects)
    )
    pair = (
        (tied.fit, tied.tied_with.fit, "tie")
        if tied is not None and tied.tied_with is not None
        else (lead.fit, lead.close_rival.fit, "confirm")
        if lead is not None and lead.close_rival is not None
        else (tied.fit, baseline, "check")
        if unneeded_only or misread
        else None
    )
    if pair is not None:
        first, second, purpose = pair
        report(f"looking for a test that tells {first.name} from {second.name}")
        phase = clock.perf_counter()
        variants = (ZERO_RUN,) if misread and purpose == "check" else VARIANTS
        separation = separating_test(problem, first, second, purpose, variants)
        seconds["separate"] = clock.perf_counter() - phase
    discovered = {}
    if decision.cause == "unexplained" or decision.left_structure:
        report("looking for what the catalog lacks in the residual (sparse regression)")
        phase = clock.perf_counter()
        discovered = discover_remainder(problem, extended, seed)
        seconds["discover"] = clock.perf_counter() - phase
    seconds["total"] = clock.perf_counter() - started
    report(
        f"cause: {decision.cause}"
        + (f" with {extended.effects[1].name()}" if len(extended.effects) > 1 else "")
        + f" ({seconds['total']:.1f} s)"
    )
    return Diagnosis(
        problem,
        baseline,
        judged,
        skipped,
        decision,
        extended,
        named,
        warnings,
        discovered,
        seconds,
        notes,
        separation,
        declared,
    )


def _diagnose_series_campaign(tests: list[Experiment], effect_catalog, progress, threads, seed):
    """Each time series alone, then the causes carried from the others to each (series/campaign.py)."""
    if any(e.is_table for e in tests):
        raise ExperimentError(
            f"{tests[0].path}: a campaign is of one kind: static tables (with supplied cyclic tests of the same "
            "muscle), or sealed time series together"
        )
    check_one_muscle(tests)
    report = progress or (lambda message: None)
    # The tests side by side, one thread each: a test's own diagnosis has stretches one thread
    # runs (its baseline, its decision, the discovery), which another test's fits fill. Each
    # report is the one a single diagnosis gives (the same with 1 or 2 threads).
    workers = min(threads or os.cpu_count() or 1, len(tests))

    def one(numbered):
        number, test = numbered
        report(f"test {number}/{len(tests)}: {test.path}")
        # Two tests report at once: each line says whose it is.
        return diagnose(test, effect_catalog, lambda message: report(f"{test.path.name}: {message}"), 1, seed)

    with thread_pool(workers) as pool:
        diagnoses = list(pool.map(one, enumerate(tests, start=1)))
    if len(diagnoses) < MIN_TESTS:
        raise ExperimentError(f"{tests[0].path}: a campaign needs at least {MIN_TESTS} tests")
    return campaign_of_series(diagnoses, effect_catalog, report, threads or 2)
