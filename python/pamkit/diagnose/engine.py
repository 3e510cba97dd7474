"""Diagnosis: calibrate the baseline on some cycles, fit every candidate effect on the same
cycles, score all of them on the cycles held out, and name a cause only when its gain is
significant."""

from __future__ import annotations

import hashlib
import math
import os
import time as clock
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares

from pamkit._core import Effect, EffectCatalog, Measurement
from pamkit.diagnose import evidence
from pamkit.diagnose.cycles import find_cycles, split_cycles
from pamkit.diagnose.model import Coordinate, Predictor, configure, effect_space
from pamkit.effects import catalog as builtin_catalog
from pamkit.experiment import Experiment, ExperimentError, load_experiment

# Effects that act only on what the instruments read: fitted on the calibrated baseline's
# prediction without simulating again.
MEASUREMENT_ONLY = {"sensor_lag", "time_skew", "sensor_offset"}
# A cause is named only if it cuts the held-out error by at least this fraction (combined over
# channels, each weighted by its noise) with a 95 % interval above zero, the information
# criterion agrees strongly (BIC down by more than 10, "very strong" evidence after Kass and
# Raftery), and its parameters are resolvable by the data (RESOLVABLE). 0.03 is ten times what
# fitting extra parameters to noise gains on held-out cycles (a few tenths of a percent).
MIN_GAIN = 0.03
MIN_BIC_DROP = 10.0
BOOTSTRAP_SAMPLES = 1000
SCAN_POINTS = 5              # simulations per physical effect's first parameter
SCAN_POINTS_MEASUREMENT = 41  # no simulation needed: scan finely (a skew has one minimum per cycle)
REFIT_LEADERS = 3             # leading candidates refitted jointly with the baseline
PAIR_TRIGGER = 1.5            # a named cause leaving a channel this many noise sigmas off tries pairs
PAIR_PARTNERS = 3             # the next candidates tried as its partner
# Finite-difference step in the unit box of each coordinate: large enough that the
# integrator's adaptive steps (relative error ~1e-7) do not swamp the slopes.
DIFF_STEP = 1e-3


@dataclass
class Fit:
    """One fitted model: which effects, their parameters, and its predictions."""

    name: str
    effects: list[Effect]
    baseline_x: np.ndarray
    params: dict[str, float]
    predicted: dict[str, np.ndarray]
    training_chi2: float
    parameter_count: int
    evaluations: int = 0
    error: str | None = None
    baseline_params: dict[str, float] = field(default_factory=dict)


@dataclass
class Problem:
    """What the fits share: data, noise scales, masks."""

    experiment: Experiment
    channels: list[str]
    measured: dict[str, np.ndarray]
    sigma: dict[str, float]
    fit_mask: np.ndarray
    held_mask: np.ndarray
    half_cycle: np.ndarray
    cycle: np.ndarray
    predictor: Predictor

    def chi(self, predicted: dict[str, np.ndarray], mask: np.ndarray) -> np.ndarray:
        return np.concatenate([((predicted[c] - self.measured[c]) / self.sigma[c])[mask] for c in self.channels])


def _unit_to_x(space: list[Coordinate], u: np.ndarray) -> np.ndarray:
    return np.array([c.lower + ui * (c.upper - c.lower) for c, ui in zip(space, u)])


def _x_to_unit(space: list[Coordinate], x: np.ndarray) -> np.ndarray:
    return np.array([(xi - c.lower) / (c.upper - c.lower) for c, xi in zip(space, x)])


def _start_unit(space: list[Coordinate]) -> np.ndarray:
    return np.clip(_x_to_unit(space, np.array([c.start for c in space])), 0.0, 1.0)


def _least_squares(residual, u0: np.ndarray, max_evaluations: int) -> np.ndarray:
    result = least_squares(residual, u0, bounds=(0.0, 1.0), method="trf", diff_step=DIFF_STEP,
                           x_scale=1.0, max_nfev=max_evaluations)
    return result.x


def _penalty(problem: Problem, scale: float) -> np.ndarray:
    """The residual of parameters that drive the model out of its range (a braid stretched
    past its fibers' length, a root not bracketed): a bad fit, not a failed diagnosis."""
    return np.full(int(problem.fit_mask.sum()) * len(problem.channels), 10.0 * (1.0 + scale))


def fit_baseline(problem: Problem) -> Fit:
    space = problem.predictor.baseline.space
    evaluations = 0
    start_chi = problem.chi(problem.predictor.predict(_unit_to_x(space, _start_unit(space)), []), problem.fit_mask)
    penalty = _penalty(problem, float(np.sqrt(np.mean(start_chi**2))))

    def residual(u):
        nonlocal evaluations
        evaluations += 1
        try:
            return problem.chi(problem.predictor.predict(_unit_to_x(space, u), []), problem.fit_mask)
        except (ValueError, RuntimeError):
            return penalty

    u = _least_squares(residual, _start_unit(space), 20 * (len(space) + 1))
    x = _unit_to_x(space, u)
    predicted = problem.predictor.predict(x, [])
    chi2 = float(np.sum(problem.chi(predicted, problem.fit_mask) ** 2))
    values = problem.predictor.baseline.values(x)
    return Fit("none", [], x, values, predicted, chi2, len(space), evaluations, baseline_params=values)


def fit_candidate(problem: Problem, baseline: Fit, make_effect, label: str, joint: bool = False,
                  start: Fit | None = None) -> Fit:
    """Fits one candidate: a scan of its first parameter from the calibrated baseline, then all
    its parameters with the baseline's. An effect on the measurement only is first fitted on
    the calibrated baseline's prediction, with no simulation; `joint` then refits it with the
    baseline too, from `start`."""
    effect = make_effect()
    space = effect_space(effect)
    base_space = problem.predictor.baseline.space
    measurement_only = effect.name() in MEASUREMENT_ONLY and not joint
    evaluations = 0
    if measurement_only:
        base_measurement = problem.predictor.measurement(baseline.baseline_x, [])

    def predict(base_x, effect_x):
        nonlocal evaluations
        evaluations += 1
        configure(effect, space, effect_x)
        if measurement_only:
            m = Measurement()
            for name in ("time_s", "elongation_m", "force_N", "pressure_kPa", "temperature_C"):
                setattr(m, name, getattr(base_measurement, name))
            return problem.predictor.select(effect.apply_to_measurement(m))
        return problem.predictor.predict(base_x, [effect])

    penalty = _penalty(problem, float(np.sqrt(baseline.training_chi2 / max(problem.fit_mask.sum(), 1))))

    def chi_or_penalty(base_x, effect_x):
        try:
            return problem.chi(predict(base_x, effect_x), problem.fit_mask)
        except (ValueError, RuntimeError):
            return penalty

    try:
        if start is not None:
            best_u = np.clip(_x_to_unit(space, np.array([c.of(start.params[c.name]) for c in space])), 0, 1)
            base_start = start.baseline_x
        else:
            # Scan the first coordinate over its range (the others at their starts).
            base_start = baseline.baseline_x
            first = _start_unit(space)
            best_u, best_chi2 = first, math.inf
            for point in np.linspace(0.0, 1.0, SCAN_POINTS_MEASUREMENT if measurement_only else SCAN_POINTS):
                u = first.copy()
                u[0] = point
                chi2 = float(np.sum(chi_or_penalty(baseline.baseline_x, _unit_to_x(space, u)) ** 2))
                if chi2 < best_chi2:
                    best_u, best_chi2 = u, chi2
        if measurement_only:
            def residual(u):
                return chi_or_penalty(baseline.baseline_x, _unit_to_x(space, u))

            u = _least_squares(residual, best_u, 30 * (len(space) + 1))
            base_x, effect_x = baseline.baseline_x, _unit_to_x(space, u)
        else:
            n_base = len(base_space)
            base_u = np.clip(_x_to_unit(base_space, base_start), 0.0, 1.0)

            def residual(u):
                return chi_or_penalty(_unit_to_x(base_space, u[:n_base]), _unit_to_x(space, u[n_base:]))

            u = _least_squares(residual, np.concatenate([base_u, best_u]), 12 * (n_base + len(space) + 1))
            base_x, effect_x = _unit_to_x(base_space, u[:n_base]), _unit_to_x(space, u[n_base:])
        configure(effect, space, effect_x)
        predicted = predict(base_x, effect_x)
        chi2 = float(np.sum(problem.chi(predicted, problem.fit_mask) ** 2))
        params = {c.name: float(c.value(v)) for c, v in zip(space, effect_x)}
        params.update(effect.options())
        count = len(space) + len(base_space)
        return Fit(label, [effect], base_x, params, predicted, chi2, count, evaluations,
                   baseline_params=problem.predictor.baseline.values(base_x))
    except (ValueError, RuntimeError) as error:  # the effect drove the model out of its range
        return Fit(label, [effect], baseline.baseline_x, {}, baseline.predicted, math.inf, len(space), evaluations,
                   error=str(error))


def fit_pair(problem: Problem, first: Fit, make_first, make_second, label: str) -> Fit:
    """Adds a second effect to a fitted one: a scan of the second's first parameter from the
    first's fit, then everything (baseline, both effects) jointly."""
    effects = [make_first(), make_second()]
    spaces = [effect_space(e) for e in effects]
    base_space = problem.predictor.baseline.space
    n_base, n_first = len(base_space), len(spaces[0])
    evaluations = 0

    def split(u):
        return (_unit_to_x(base_space, u[:n_base]), _unit_to_x(spaces[0], u[n_base:n_base + n_first]),
                _unit_to_x(spaces[1], u[n_base + n_first:]))

    def predict(u):
        nonlocal evaluations
        evaluations += 1
        base_x, x1, x2 = split(u)
        configure(effects[0], spaces[0], x1)
        configure(effects[1], spaces[1], x2)
        return problem.predictor.predict(base_x, effects)

    penalty = _penalty(problem, float(np.sqrt(first.training_chi2 / max(problem.fit_mask.sum(), 1))))

    def residual(u):
        try:
            return problem.chi(predict(u), problem.fit_mask)
        except (ValueError, RuntimeError):
            return penalty

    start = np.concatenate([
        np.clip(_x_to_unit(base_space, first.baseline_x), 0, 1),
        np.clip(_x_to_unit(spaces[0], np.array([c.of(first.params[c.name]) for c in spaces[0]])), 0, 1),
        _start_unit(spaces[1]),
    ])
    best_u, best_chi2 = start, math.inf
    # Finer than a single effect's scan: the first effect already absorbed part of the second.
    for point in np.linspace(0.0, 1.0, 2 * SCAN_POINTS - 1):
        u = start.copy()
        u[n_base + n_first] = point
        chi2 = float(np.sum(residual(u) ** 2))
        if chi2 < best_chi2:
            best_u, best_chi2 = u, chi2
    u = _least_squares(residual, best_u, 10 * (len(start) + 1))
    try:
        predicted = predict(u)
    except (ValueError, RuntimeError) as error:
        return Fit(label, effects, first.baseline_x, {}, first.predicted, math.inf, len(start), evaluations, error=str(error))
    base_x, x1, x2 = split(u)
    params = {}
    for effect, space, x in zip(effects, spaces, (x1, x2)):
        params.update({f"{effect.name()}.{c.name}": float(c.value(v)) for c, v in zip(space, x)})
        params.update({f"{effect.name()}.{k}": v for k, v in effect.options().items()})
    chi2 = float(np.sum(problem.chi(predicted, problem.fit_mask) ** 2))
    return Fit(label, effects, base_x, params, predicted, chi2, len(start), evaluations,
               baseline_params=problem.predictor.baseline.values(base_x))


def structured(problem: Problem, fit: Fit) -> list[str]:
    """Channels whose held-out residual is still well above their noise (RMS > 1.5 sigma)."""
    return [c for c in problem.channels
            if evidence.rmse((fit.predicted[c] - problem.measured[c])[problem.held_mask]) > PAIR_TRIGGER * problem.sigma[c]]


@dataclass
class Score:
    rmse: dict[str, float]
    gain: dict[str, float]
    gain_ci95: dict[str, list[float]]
    combined_gain: float
    combined_ci95: list[float]
    delta_bic: float


def score(problem: Problem, baseline: Fit, fit: Fit, rng: np.random.Generator) -> Score:
    """Held-out RMSE per channel, gain against the baseline, bootstrap intervals over held-out
    half-cycles, and the change of the Bayesian information criterion on the fitted cycles."""
    units = np.unique(problem.half_cycle[problem.held_mask])
    sse_base = np.zeros((len(problem.channels), units.size))
    sse_fit = np.zeros_like(sse_base)
    counts = np.zeros(units.size)
    for j, unit in enumerate(units):
        mask = problem.held_mask & (problem.half_cycle == unit)
        counts[j] = mask.sum()
        for i, c in enumerate(problem.channels):
            sse_base[i, j] = np.sum((baseline.predicted[c] - problem.measured[c])[mask] ** 2)
            sse_fit[i, j] = np.sum((fit.predicted[c] - problem.measured[c])[mask] ** 2)
    weights = np.array([1.0 / problem.sigma[c] ** 2 for c in problem.channels])[:, None]
    n = counts.sum()
    rmse = {c: float(np.sqrt(sse_fit[i].sum() / n)) for i, c in enumerate(problem.channels)}
    gain = {c: _gain(sse_fit[i].sum(), sse_base[i].sum()) for i, c in enumerate(problem.channels)}
    combined = _gain((weights * sse_fit).sum(), (weights * sse_base).sum())
    draws = rng.integers(0, units.size, size=(BOOTSTRAP_SAMPLES, units.size))
    boot_fit = sse_fit[:, draws].sum(axis=2)
    boot_base = sse_base[:, draws].sum(axis=2)
    gain_ci = {}
    for i, c in enumerate(problem.channels):
        gains = 1.0 - np.sqrt(boot_fit[i] / np.maximum(boot_base[i], 1e-300))
        gain_ci[c] = [float(np.percentile(gains, 2.5)), float(np.percentile(gains, 97.5))]
    combined_boot = 1.0 - np.sqrt((weights * boot_fit).sum(axis=0) / np.maximum((weights * boot_base).sum(axis=0), 1e-300))
    combined_ci = [float(np.percentile(combined_boot, 2.5)), float(np.percentile(combined_boot, 97.5))]
    n_fit = int(problem.fit_mask.sum()) * len(problem.channels)
    delta_bic = (fit.training_chi2 - baseline.training_chi2) + (fit.parameter_count - baseline.parameter_count) * math.log(n_fit)
    return Score(rmse, gain, gain_ci, combined, combined_ci, float(delta_bic))


def _gain(sse_fit: float, sse_base: float) -> float:
    return float(1.0 - math.sqrt(sse_fit / sse_base)) if sse_base > 0 else 0.0


# An effect smaller than one sample resolves is not named: a skew or lag shorter than the
# sampling interval, or slack shorter than the crosshead's travel between two samples, is
# within what synchronising two instruments leaves (a clock drifting by 50 ppm over a 400 s
# test is 20 ms) and mimics a sub-sample shift of the channels.
def _sample_interval(problem: Problem) -> float:
    return float(np.median(np.diff(problem.experiment.time_s)))


def _travel_per_sample(problem: Problem) -> float:
    steps = np.abs(np.diff(problem.experiment.elongation_m))
    moving = steps[steps > 0.1 * steps.max()] if steps.max() > 0 else steps
    return float(np.median(moving)) if moving.size else 0.0


RESOLVABLE = {
    "time_skew": lambda params, problem: abs(params["offset_s"]) >= _sample_interval(problem),
    "sensor_lag": lambda params, problem: params["time_constant_s"] >= _sample_interval(problem),
    "fixture_slack": lambda params, problem: params["slack_m"] >= _travel_per_sample(problem),
}


def significant(problem: Problem, fit: Fit, s: Score) -> bool:
    resolvable = all(RESOLVABLE.get(e.name(), lambda p, q: True)(fit.params, problem) for e in fit.effects)
    return (s.combined_gain >= MIN_GAIN and s.combined_ci95[0] > 0.0 and s.delta_bic < -MIN_BIC_DROP
            and resolvable)


def candidates(effect_catalog: EffectCatalog, problem: Problem) -> list[tuple[str, object]]:
    """(label, factory) for every catalog effect that can act in this test; effects with a
    channel option become one candidate per measured channel."""
    out = []
    for name in effect_catalog.names():
        probe = effect_catalog.make(name)
        acts, _ = probe.acts_in(problem.predictor.mode)
        if not acts:
            continue
        if "channel" in probe.options():
            for channel in problem.channels:
                out.append((f"{name}:channel={channel}", lambda n=name, c=channel: effect_catalog.parse(f"{n}:channel={c}")))
        else:
            out.append((name, lambda n=name: effect_catalog.make(n)))
    return out


# Units that cannot be right: (column, lowest, highest plausible value, what it looks like instead).
PLAUSIBLE = {
    "elongation_m": (-0.5, 0.5, "millimetres"),
    "force_N": (-1e4, 1e5, "the wrong unit"),
    "pressure_kPa": (-101.0, 2000.0, "pascals or psi"),
    "temperature_C": (-50.0, 150.0, "kelvin"),
}


def check_units(experiment: Experiment) -> None:
    """Raises ExperimentError naming the file, row and column of the first value whose size
    says its unit is wrong (elongation in mm, pressure in Pa, temperature in K)."""
    names = list(experiment.columns)
    for name, (low, high, looks_like) in PLAUSIBLE.items():
        if name not in experiment.columns:
            continue
        values = experiment.columns[name]
        bad = np.flatnonzero((values < low) | (values > high))
        if bad.size:
            row = int(bad[0])
            raise ExperimentError(
                f"{experiment.data_path}:{row + 2}: column {names.index(name) + 1} ({name}) = {values[row]:g} is outside "
                f"[{low:g}, {high:g}]: is it in {looks_like}?"
            )


def build_problem(experiment: Experiment) -> Problem:
    check_units(experiment)
    channels = experiment.measured()
    if experiment.gas == "supplied":
        channels = [c for c in channels if c != "pressure_kPa"]  # an input there, not a prediction
    if not channels:
        raise ExperimentError(
            f"{experiment.data_path}: no measured channel to compare with (needs force_N, pressure_kPa or "
            "temperature_C besides time_s and elongation_m)"
        )
    elongation = experiment.elongation_m
    cycles = find_cycles(elongation)
    try:
        fit_cycles, held_cycles = split_cycles(cycles)
    except ValueError as error:
        raise ExperimentError(f"{experiment.data_path}: column elongation_m: {error}") from None
    cycle = cycles.index(elongation.size)
    measured = {c: experiment.columns[c] for c in channels}
    sigma = {c: evidence.noise_scale(measured[c]) for c in channels}
    return Problem(
        experiment=experiment,
        channels=channels,
        measured=measured,
        sigma=sigma,
        fit_mask=np.isin(cycle, fit_cycles),
        held_mask=np.isin(cycle, held_cycles),
        half_cycle=cycles.half_cycle_index(elongation),
        cycle=cycle,
        predictor=Predictor(experiment, channels),
    )


def _try_pairs(problem, baseline, single, single_score, fitted, factories, rng, threads, report):
    """The named cause leaves structure: pair it with the next candidates, and keep a pair
    only if it beats the single cause as the single beat the baseline (significant gain over
    it on held-out cycles, BIC, resolvable)."""
    partners = [fit for fit, _ in fitted if fit.effects[0].name() != single.effects[0].name()][:PAIR_PARTNERS]
    report(f"{single.name} leaves {', '.join(structured(problem, single))} above noise: trying it with "
           f"{', '.join(p.name for p in partners)}")
    best, best_score = single, single_score
    with ThreadPoolExecutor(max_workers=threads or os.cpu_count() or 1) as pool:
        futures = [pool.submit(fit_pair, problem, single, factories[single.name], factories[p.name],
                               f"{single.name}+{p.name}") for p in partners]
        for future in futures:
            pair = future.result()
            if pair.error is not None:
                continue
            over_single = score(problem, single, pair, rng)
            second = pair.effects[1].name()
            second_params = {k.split(".", 1)[1]: v for k, v in pair.params.items() if k.startswith(second + ".")}
            resolvable = RESOLVABLE.get(second, lambda p, q: True)(second_params, problem)
            if (over_single.combined_gain >= MIN_GAIN and over_single.combined_ci95[0] > 0
                    and over_single.delta_bic < -MIN_BIC_DROP and resolvable):
                pair_score = score(problem, baseline, pair, rng)
                if pair_score.combined_gain > best_score.combined_gain:
                    best, best_score = pair, pair_score
    return best, best_score


@dataclass
class Diagnosis:
    """Everything the report says; see report.py for the JSON, text and plot."""

    problem: Problem
    baseline: Fit
    candidates: list[tuple[Fit, Score]]
    skipped: dict[str, str]
    extended: Fit
    extended_score: Score | None
    cause: str
    seconds: dict[str, float] = field(default_factory=dict)


def data_seed(problem: Problem) -> int:
    """A seed drawn from the measured channels' bytes (little-endian float64, whatever the
    machine): the same data give the same bootstrap draws, on every run and machine."""
    digest = hashlib.sha256()
    for c in problem.channels:
        digest.update(c.encode())
        digest.update(np.ascontiguousarray(problem.measured[c], dtype="<f8").tobytes())
    return int.from_bytes(digest.digest()[:8], "little")


def diagnose(experiment: Experiment | str | Path, effect_catalog: EffectCatalog | None = None, progress=None,
             threads: int | None = None, seed: int | None = None) -> Diagnosis:
    """Diagnoses one experiment. `progress(message)` is called as work proceeds. `seed` seeds
    the bootstrap; by default it comes from the measured data (data_seed).

    Raises:
        ExperimentError: for data that cannot be diagnosed, naming file, row and column.
    """
    started = clock.perf_counter()
    report = progress or (lambda message: None)
    if not isinstance(experiment, Experiment):
        experiment = load_experiment(experiment)
    effect_catalog = effect_catalog if effect_catalog is not None else builtin_catalog()
    problem = build_problem(experiment)
    seconds = {}

    report(f"calibrating the baseline on {len(np.unique(problem.cycle[problem.fit_mask]))} cycles "
           f"({', '.join(problem.channels)})")
    baseline = fit_baseline(problem)
    seconds["baseline"] = clock.perf_counter() - started

    skipped = {}
    for name in effect_catalog.names():
        acts, why_not = effect_catalog.make(name).acts_in(problem.predictor.mode)
        if not acts:
            skipped[name] = why_not
    todo = candidates(effect_catalog, problem)
    rng = np.random.default_rng(data_seed(problem) if seed is None else seed)
    fitted: list[tuple[Fit, Score]] = []
    phase = clock.perf_counter()
    with ThreadPoolExecutor(max_workers=threads or os.cpu_count() or 1) as pool:
        futures = [(label, pool.submit(fit_candidate, problem, baseline, factory, label)) for label, factory in todo]
        for done, (label, future) in enumerate(futures, start=1):
            fit = future.result()
            if fit.error is None:
                fitted.append((fit, score(problem, baseline, fit, rng)))
            else:
                skipped[label] = f"fit failed: {fit.error}"
            report(f"[{done}/{len(futures)}] {label}: "
                   + (f"held-out gain {fitted[-1][1].combined_gain:+.3f}" if fit.error is None else "failed"))
    seconds["candidates"] = clock.perf_counter() - phase
    fitted.sort(key=lambda item: (-item[1].combined_gain, item[1].delta_bic))
    # The leading effects on the measurement were fitted on the baseline's prediction; refit
    # them with the baseline too, so they compete on equal terms with the physical ones.
    factories = dict(todo)
    leaders = [i for i, (fit, _) in enumerate(fitted[:REFIT_LEADERS]) if fit.effects[0].name() in MEASUREMENT_ONLY]
    if leaders:
        report(f"refitting {', '.join(fitted[i][0].name for i in leaders)} with the baseline")
        with ThreadPoolExecutor(max_workers=threads or os.cpu_count() or 1) as pool:
            refits = {i: pool.submit(fit_candidate, problem, baseline, factories[fitted[i][0].name], fitted[i][0].name,
                                     True, fitted[i][0]) for i in leaders}
            for i, future in refits.items():
                fit = future.result()
                if fit.error is None and fit.training_chi2 < fitted[i][0].training_chi2:
                    fitted[i] = (fit, score(problem, baseline, fit, rng))
        fitted.sort(key=lambda item: (-item[1].combined_gain, item[1].delta_bic))

    named = [(fit, s) for fit, s in fitted if significant(problem, fit, s)]
    if named:
        cause, extended, extended_score = named[0][0].effects[0].name(), named[0][0], named[0][1]
    else:
        cause, extended, extended_score = "none", baseline, None
    if cause != "none" and structured(problem, extended):
        extended, extended_score = _try_pairs(problem, baseline, extended, extended_score, fitted, factories, rng,
                                              threads, report)
    seconds["total"] = clock.perf_counter() - started
    report(f"cause: {cause}" + (f" with {extended.effects[1].name()}" if len(extended.effects) > 1 else "")
           + f" ({seconds['total']:.1f} s)")
    return Diagnosis(problem, baseline, fitted, skipped, extended, extended_score, cause, seconds)
