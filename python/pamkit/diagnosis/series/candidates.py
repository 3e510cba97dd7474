"""Fitting each catalog and user effect on the fitted units.

An effect on the physics or the motion is fitted with the baseline's parameters free (a scan of
its first parameter from the calibrated baseline, then everything jointly). An effect on the
measurement only is first fitted on the calibrated baseline's prediction; the leading ones are
then refitted with the baseline free too, since the baseline's calibration has absorbed part of
them (an offset pulls the inflation pressure to its bound). Such a refit could make the effect a
general corrector — the inflation pressure and bladder scale move to fit the force while a
pressure offset undoes that on the pressure channel — so its gain is counted only on the
channels the effect changes, and it must not make the others worse (decide.py: an effect earns
credit only where it acts).

A physics or motion effect is screened before its joint fit: one Gauss-Newton step from its scan,
with the calibrated baseline and every parameter of the effect free, predicts how far a fit could
lower the fitted chi-square, and one that could not lower it by SCREEN_DROP is left where that step
lands (a model run there scores it; engine.py fits it through if even that is significant). The
report says which.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import lsq_linear

from pamkit._core import EffectCatalog, EffectStage, GasMode, Resolution
from pamkit.diagnosis import evidence
from pamkit.diagnosis.coordinates import configure
from pamkit.diagnosis.series.calibrate import (
    Fit,
    baseline_coordinates,
    cluster_intervals,
    least_squares_in_box,
    penalty,
    start_unit,
    strain_at_bounds,
    unit_to_x,
    x_to_unit,
)
from pamkit.diagnosis.series.jacobian import DIFF_STEP, SENSITIVITY_STEP, forward_differences, jacobian_for
from pamkit.diagnosis.series.kinds import Problem

SCAN_POINTS = 5  # simulations per physical effect's first parameter
SCAN_POINTS_MEASUREMENT = 41  # no simulation needed: scan finely (a skew has one minimum per cycle)
# A joint fit stops when a step lowers its chi-square by less than this share of it. SciPy's
# default, 1e-8, spent 12 % of the diagnoses' CPU on digits no decision reads: over 353 diagnoses
# of the four decision worlds, every verdict the same, the held-out gains moved by a median 0 and
# at most 2e-3, on candidates gaining nothing, against decision margins of 8e-4 and more.
JOINT_FTOL = 1e-6
# A candidate whose one Gauss-Newton step from its scan (the calibrated baseline free, the step
# bounded to the search box) lowers the fitted chi-square by less than this share is not fitted
# further: a held-out gain of MIN_GAIN (0.03) needs a drop near 6 %. Over the 353 diagnoses of four
# decision worlds, 1021 of 1774 physics and motion candidates of one parameter were screened, and
# fitted through anyway none was significant (the best gained 0.026); with the viscoelastic
# bladder's two parameters stepped together, 224 of its 298 fits too, every cause the same.
SCREEN_DROP = 0.02
# An effect moves a channel where its fit's prediction differs from the model's without it by more
# than this share of the channel's noise at some sample. A channel it cannot reach differs only by
# the integrator's steps, which the effect's states may change: at the diagnosis's rtol 1e-6, a
# viscoelastic bladder moved a sealed test's force by 22-29 noise sigmas and its gauge pressure by
# 2e-12-4e-12 of its noise (bench_diagnose seeds 1001 and 1013, measured apart).
MOVES_CHANNEL = 1e-3
# The error of a pair that a step showed could not lower the chi-square it was fitted to beat.
SCREENED_OUT = "screened out"


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
            channels = list(problem.channels)
            # A supplied test's pressure is an input, not a compared channel; an instrument
            # error there acts on what drives the model (a hose's lag).
            supplied = problem.predictor.mode == GasMode.supplied
            if supplied and effect_catalog.parse(f"{name}:channel=gauge_pressure_Pa").reads_supplied_pressure():
                channels.append("gauge_pressure_Pa")
            for channel in channels:
                out.append(
                    (f"{name}:channel={channel}", lambda n=name, c=channel: effect_catalog.parse(f"{n}:channel={c}"))
                )
        else:
            out.append((name, lambda n=name: effect_catalog.make(n)))
    return out


def lag_start(problem: Problem, baseline: Fit, effect, space) -> list[float]:
    """Where a time shift of one channel (a skew, a lag: a measurement effect whose first parameter
    must resolve the sample interval) starts its search, from the data: the lag at which the
    channel's measured rate best correlates with the calibrated baseline's predicted rate, within
    the search interval. The least-squares surface of a shift is periodic with the cycles, and a
    baseline calibrated on skewed data has bent its own shape towards them: a grid on it may rank
    another cycle's minimum first (a 1.65 s skew fitted at 4.0 s), where the bounded search stays.
    The cross-correlation of the rates does not depend on the baseline's shape. Empty for any other
    effect."""
    channel = effect.options().get("channel")
    parameters = effect.parameters()
    if (
        effect.stage() != EffectStage.measurement
        or channel not in problem.channels
        or not space
        or parameters[0].resolution != Resolution.sample_interval
    ):
        return []
    time = problem.experiment.time_s
    interval = float(np.median(np.diff(time)))
    low, high = sorted(space[0].value(x) for x in (space[0].lower, space[0].upper))
    longest = min(int(max(abs(low), abs(high)) / interval), time.size // 2)
    if longest < 1:
        return []
    correlation = evidence.lagged_correlations(
        np.gradient(problem.measured[channel], time), np.gradient(baseline.predicted[channel], time), longest
    )
    lags = np.arange(-longest, longest + 1) * interval
    inside = (lags >= low) & (lags <= high) & (lags != 0.0)
    if not inside.any():
        return []
    return [float(lags[inside][np.argmax(correlation[inside])])]


def _effect_coordinates(effect, space, x, prefix: str = "") -> dict:
    return {prefix + c.name: (c, float(v)) for c, v in zip(space, x)}


def fit_candidate(
    problem: Problem, baseline: Fit, make_effect, label: str, start: Fit | None = None, screen: bool = False
) -> Fit:
    """Fits one candidate effect (module docstring). With `start` (a measurement effect's fit on
    the calibrated baseline), refits it jointly with the baseline from there. With `screen`, an
    effect on the physics or the motion takes one Gauss-Newton step from its scan first, every
    parameter of the effect in the step (the scan explores only the first: a
    step in it alone sees nothing of a viscoelastic branch's strength), and where that lowers the
    fitted chi-square by less than SCREEN_DROP, is left there (`Fit.screened`). A refit screened
    the same way, its step from `start` with the baseline free on the refit's own first Jacobian,
    returns `start` itself: the effect stays where its fit on the calibrated baseline put it."""
    effect = make_effect()
    space = problem.search_space(effect)
    base_space = problem.predictor.baseline.space
    measurement_only = effect.stage() == EffectStage.measurement and start is None
    # A transducer whose reading drives a supplied test changes the model's input: its fit runs
    # the model (on the calibrated baseline), not only the instruments' stage.
    drives_model = problem.experiment.gas == GasMode.supplied and effect.reads_supplied_pressure()
    evaluations = 0

    def counted():
        nonlocal evaluations
        evaluations += 1

    if measurement_only and not drives_model:
        base_measurement = problem.predictor.measurement(baseline.baseline_x, [])

    def predict(base_x, effect_x):
        nonlocal evaluations
        evaluations += 1
        configure(effect, space, effect_x)
        if measurement_only and not drives_model:
            # The instrument reads the base run into a new measurement; the run stays as it was.
            return problem.predictor.select(effect.apply_to_measurement(base_measurement))
        return problem.predictor.predict(base_x, [effect])

    bad_fit = penalty(problem, float(np.sqrt(sum(baseline.training_chi2.values()) / max(problem.fit_mask.sum(), 1))))

    def chi_or_penalty(base_x, effect_x):
        try:
            return problem.chi(predict(base_x, effect_x), problem.fit_mask)
        except (ValueError, RuntimeError):
            return bad_fit

    try:
        starts = []  # further starts of a joint refit: a shift's lag from the data (lag_start)
        if start is not None:
            best_u = np.clip(x_to_unit(space, np.array([c.of(start.params[c.name]) for c in space])), 0, 1)
            interval = float(np.median(np.diff(problem.experiment.time_s)))
            for lag in lag_start(problem, baseline, effect, space):
                if abs(lag - start.params[space[0].name]) > interval:
                    other = best_u.copy()
                    other[0] = np.clip(x_to_unit(space[:1], np.array([space[0].of(lag)]))[0], 0, 1)
                    starts.append(other)
        elif not space:  # every parameter held: only the baseline moves
            best_u = np.array([])
        else:
            # Scan the first coordinate over its range (the others at their starts).
            first = start_unit(space)
            best_u, best_chi2, best_chi = first, math.inf, None
            grid = np.linspace(0.0, 1.0, SCAN_POINTS_MEASUREMENT if measurement_only else SCAN_POINTS)
            lags = lag_start(problem, baseline, effect, space) if measurement_only else []
            for point in [
                *grid,
                *(float(np.clip(x_to_unit(space[:1], np.array([space[0].of(v)]))[0], 0, 1)) for v in lags),
            ]:
                u = first.copy()
                u[0] = point
                chi = chi_or_penalty(baseline.baseline_x, unit_to_x(space, u))
                chi2 = float(np.sum(chi**2))
                if chi2 < best_chi2:
                    best_u, best_chi2, best_chi = u, chi2, chi
        if measurement_only:

            def residual(u):
                return chi_or_penalty(baseline.baseline_x, unit_to_x(space, u))

            # The instruments read one fixed run (or a supplied test's model, without an ODE): their
            # differences at the sensitivities' small step are as exact as the sealed fits' Jacobians.
            result = (
                least_squares_in_box(
                    residual,
                    best_u,
                    30 * (len(space) + 1),
                    jac=lambda u: forward_differences(residual, u, SENSITIVITY_STEP),
                )
                if space
                else None
            )
            u = result.x if result is not None else best_u
            base_x, effect_x = baseline.baseline_x, unit_to_x(space, u)
            count = len(space)
            fitted_space = space
        else:
            n_base = len(base_space)
            base_u = np.clip(x_to_unit(base_space, baseline.baseline_x), 0.0, 1.0)
            # A baseline coordinate the calibration left at a search bound is straining to absorb
            # what the candidate may explain; from the bound, the bounded solver may never leave
            # it (the answer then flips with rounding). The joint fit starts it from its declared
            # start instead, free to go either way.
            at_bound = [c.at_bound(x) is not None for c, x in zip(base_space, baseline.baseline_x)]
            base_u = np.where(at_bound, start_unit(base_space), base_u)

            def residual(u):
                return chi_or_penalty(unit_to_x(base_space, u[:n_base]), unit_to_x(space, u[n_base:]))

            def point(u):
                return unit_to_x(base_space, u[:n_base]), [
                    configure(make_effect(), space, unit_to_x(space, u[n_base:]))
                ]

            calibrated = np.concatenate([np.clip(x_to_unit(base_space, baseline.baseline_x), 0.0, 1.0), best_u])
            chi2_baseline = sum(baseline.training_chi2.values())
            if screen and start is None and space and baseline.jacobian is not None:
                drop, landed = one_step(residual, best_chi, baseline.jacobian, calibrated, chi2_baseline, len(space))
                if drop < SCREEN_DROP:
                    return _stepped(problem, label, effect, space, base_space, landed, predict, evaluations, drop)
            jac = jacobian_for(problem, point, residual, counted)
            if screen and start is not None:
                first = jac(calibrated)
                drop, _ = stepped_drop(first, residual(calibrated), calibrated, chi2_baseline)
                if drop < SCREEN_DROP:
                    return start
                jac = _knowing(jac, calibrated, first)
            results = [
                least_squares_in_box(
                    residual, np.concatenate([base_u, u0]), 12 * (n_base + len(space) + 1), jac=jac, ftol=JOINT_FTOL
                )
                for u0 in [best_u, *starts]
            ]
            result = min(results, key=lambda r: r.cost)  # the fit's own objective, never the held-out units
            u = result.x
            base_x, effect_x = unit_to_x(base_space, u[:n_base]), unit_to_x(space, u[n_base:])
            count = len(space) + n_base
            fitted_space = base_space + space
        configure(effect, space, effect_x)
        predicted = predict(base_x, effect_x)
        note_moved_channels(problem, effect, base_x, predicted)
        bands, undetermined = (
            cluster_intervals(fitted_space, u, result.jac, result.fun, problem.residual_units())
            if result is not None
            else ([], {})
        )
        # A measurement effect keeps the calibrated baseline: counted as one model with it.
        total = count + (len(base_space) if measurement_only else 0)
        fit = _effect_fit(problem, label, effect, space, base_x, effect_x, predicted, not measurement_only)
        fit.parameter_count, fit.evaluations = total, evaluations
        fit.intervals = {c.name: band for c, band in zip(fitted_space, bands)}
        fit.undetermined = undetermined
        if result is not None and not measurement_only:
            fit.strain = _baseline_strain(base_space, fitted_space, u, result)
        return fit
    except (ValueError, RuntimeError) as error:  # the effect drove the model out of its range
        return Fit(
            label, [effect], baseline.baseline_x, {}, baseline.predicted, {}, len(space), evaluations, error=str(error)
        )


def note_moved_channels(problem: Problem, effect, base_x: np.ndarray, predicted: dict[str, np.ndarray]) -> None:
    """Records in `problem.moved_channels` the channels an effect on the physics or the motion moves
    in this test (`predicted`, its fit, against the model without it at the same baseline `base_x`:
    one run), once per effect: a bladder's viscoelasticity moves the force of a muscle a tensile
    machine stretches, not its gas, whose volume the braid alone sets. An effect that moved nothing
    here (fitted at its neutral values), or without which the model cannot run at that baseline, is
    left to a later fit: credited on every channel until one moves."""
    if effect.channels_changed() or effect.name() in problem.moved_channels:
        return
    try:
        without = problem.predictor.predict(base_x, [])
    except (ValueError, RuntimeError):
        return  # the fit stands; what it moves is not known here
    moved = [
        c
        for c in problem.channels
        if np.max(np.abs(np.asarray(predicted[c]) - np.asarray(without[c])), initial=0.0)
        > MOVES_CHANNEL * problem.sigma[c]
    ]
    if moved:
        problem.moved_channels[effect.name()] = moved


def _knowing(jac, at: np.ndarray, known: np.ndarray):
    """`jac` with its value at `at` already computed: a refit starts where its screen stepped from,
    and that run with sensitivities is not made twice."""
    return lambda u: known.copy() if np.array_equal(u, at) else jac(u)


def _baseline_strain(base_space, fitted_space, u: np.ndarray, result) -> dict[str, tuple[float, float]]:
    """What the baseline's bounds cost a joint fit (calibrate.strain_at_bounds): judge does not
    hold a bound that costs nothing against the candidate."""
    moved = {c.name for c in base_space}
    return {k: v for k, v in strain_at_bounds(fitted_space, u, result.jac, result.fun).items() if k in moved}


def one_step(
    residual, r: np.ndarray, baseline_jacobian: np.ndarray, u: np.ndarray, chi2_baseline: float, count: int = 1
) -> tuple[float, np.ndarray]:
    """The drop of the fitted chi-square, as a share of the calibrated baseline's, that one
    Gauss-Newton step from `u` (the calibrated baseline's coordinates, then the effect's `count`
    last; `r` the residual there, which the scan computed) predicts, the step bounded to the unit
    box (a linear least-squares problem, scipy.optimize.lsq_linear); and where the step lands. The
    Jacobian is the calibrated baseline's, already computed, beside a difference quotient for each
    of the effect's coordinates: one model run each, where the joint fit's first Jacobian would be
    one run per coordinate of the baseline too."""
    columns = []
    for index in range(len(u) - count, len(u)):
        h = DIFF_STEP if u[index] + DIFF_STEP <= 1.0 else -DIFF_STEP
        columns.append((residual(u + h * np.eye(len(u))[index]) - r) / h)
    return stepped_drop(np.column_stack([baseline_jacobian, *columns]), r, u, chi2_baseline)


def stepped_drop(jacobian: np.ndarray, r: np.ndarray, u: np.ndarray, chi2_baseline: float) -> tuple[float, np.ndarray]:
    """The drop of the fitted chi-square, as a share of the calibrated baseline's, that the
    Gauss-Newton step from `u` with this `jacobian` (residual `r` there), bounded to the unit box,
    predicts; and where the step lands."""
    step = lsq_linear(jacobian, -r, bounds=(-u, 1.0 - u)).x
    predicted = float(np.sum((r + jacobian @ step) ** 2))
    return (1.0 - predicted / chi2_baseline if chi2_baseline > 0 else 0.0), np.clip(u + step, 0.0, 1.0)


def _stepped(problem: Problem, label, effect, space, base_space, u, predict, evaluations, drop) -> Fit:
    """The candidate where its screening step landed: a model run there, no intervals."""
    n_base = len(base_space)
    base_x, effect_x = unit_to_x(base_space, u[:n_base]), unit_to_x(space, u[n_base:])
    predicted = predict(base_x, effect_x)
    note_moved_channels(problem, effect, base_x, predicted)
    fit = _effect_fit(problem, label, effect, space, base_x, effect_x, predicted, True)
    fit.parameter_count, fit.evaluations, fit.screened = n_base + len(space), evaluations + 1, drop
    return fit


def _effect_fit(problem: Problem, label, effect, space, base_x, effect_x, predicted, baseline_moved: bool) -> Fit:
    """One effect's fit at `effect_x` over the baseline at `base_x`, its prediction scored on the
    fitted units; the baseline's coordinates among its own where the fit moved them."""
    params = {c.name: float(c.value(v)) for c, v in zip(space, effect_x)}
    params.update(effect.options())
    coordinates = baseline_coordinates(problem, base_x) if baseline_moved else {}
    coordinates.update(_effect_coordinates(effect, space, effect_x))
    return Fit(
        label,
        [effect],
        base_x,
        params,
        predicted,
        problem.chi2_by_channel(predicted),
        len(space),
        baseline_params=problem.predictor.baseline.values(base_x),
        coordinates=coordinates,
    )


def fit_pair(problem: Problem, first: Fit, make_first, make_second, label: str, beat: float | None = None) -> Fit:
    """Adds a second effect to a fitted one: a scan of the second's first parameter from the
    first's fit, then everything (baseline, both effects) jointly. With `beat` (a fitted
    chi-square the pair is there to lower), one Gauss-Newton step from the scan's best point first:
    where it lowers `beat` by less than SCREEN_DROP, the pair is not fitted further and comes back
    with an `error` that begins with SCREENED_OUT."""
    effects = [make_first(), make_second()]
    spaces = [problem.search_space(e) for e in effects]
    base_space = problem.predictor.baseline.space
    n_base, n_first = len(base_space), len(spaces[0])
    evaluations = 0

    def counted():
        nonlocal evaluations
        evaluations += 1

    def split(u):
        return (
            unit_to_x(base_space, u[:n_base]),
            unit_to_x(spaces[0], u[n_base : n_base + n_first]),
            unit_to_x(spaces[1], u[n_base + n_first :]),
        )

    def predict(u):
        nonlocal evaluations
        evaluations += 1
        base_x, x1, x2 = split(u)
        configure(effects[0], spaces[0], x1)
        configure(effects[1], spaces[1], x2)
        return problem.predictor.predict(base_x, effects)

    bad_fit = penalty(problem, float(np.sqrt(sum(first.training_chi2.values()) / max(problem.fit_mask.sum(), 1))))

    def residual(u):
        try:
            return problem.chi(predict(u), problem.fit_mask)
        except (ValueError, RuntimeError):
            return bad_fit

    start = np.concatenate(
        [
            np.clip(x_to_unit(base_space, first.baseline_x), 0, 1),
            np.clip(x_to_unit(spaces[0], np.array([c.of(first.params[c.name]) for c in spaces[0]])), 0, 1),
            start_unit(spaces[1]),
        ]
    )
    best_u, best_chi2 = start, math.inf
    # Finer than a single effect's scan: the first effect already absorbed part of the second.
    for point in np.linspace(0.0, 1.0, 2 * SCAN_POINTS - 1) if spaces[1] else ():
        u = start.copy()
        u[n_base + n_first] = point
        chi2 = float(np.sum(residual(u) ** 2))
        if chi2 < best_chi2:
            best_u, best_chi2 = u, chi2

    def point(u):
        base_x, x1, x2 = split(u)
        return base_x, [
            configure(make(), space, x) for make, space, x in zip((make_first, make_second), spaces, (x1, x2))
        ]

    jac = jacobian_for(problem, point, residual, counted)
    if beat is not None:
        first_jacobian = jac(best_u)
        drop, _ = stepped_drop(first_jacobian, residual(best_u), best_u, beat)
        if drop < SCREEN_DROP:
            return Fit(
                label,
                effects,
                first.baseline_x,
                {},
                first.predicted,
                {},
                len(start),
                evaluations,
                error=(
                    f"{SCREENED_OUT}: one Gauss-Newton step lowers the fitted chi-square {100 * drop:.1f} % below the "
                    f"one to beat, where {100 * SCREEN_DROP:g} % is needed"
                ),
            )
        jac = _knowing(jac, best_u, first_jacobian)
    result = least_squares_in_box(residual, best_u, 10 * (len(start) + 1), jac=jac)
    u = result.x
    try:
        predicted = predict(u)
    except (ValueError, RuntimeError) as error:
        return Fit(label, effects, first.baseline_x, {}, first.predicted, {}, len(start), evaluations, error=str(error))
    base_x, x1, x2 = split(u)
    params = {}
    coordinates = baseline_coordinates(problem, base_x)
    for effect, space, x in zip(effects, spaces, (x1, x2)):
        params.update({f"{effect.name()}.{c.name}": float(c.value(v)) for c, v in zip(space, x)})
        params.update({f"{effect.name()}.{k}": v for k, v in effect.options().items()})
        coordinates.update(_effect_coordinates(effect, space, x, prefix=f"{effect.name()}."))
    names = [c.name for c in base_space] + [f"{e.name()}.{c.name}" for e, space in zip(effects, spaces) for c in space]
    bands, undetermined = cluster_intervals(
        base_space + spaces[0] + spaces[1], u, result.jac, result.fun, problem.residual_units()
    )
    intervals = dict(zip(names, bands))
    rename = dict(zip([c.name for c in base_space + spaces[0] + spaces[1]], names))
    return Fit(
        label,
        effects,
        base_x,
        params,
        predicted,
        problem.chi2_by_channel(predicted),
        len(start),
        evaluations,
        baseline_params=problem.predictor.baseline.values(base_x),
        coordinates=coordinates,
        intervals=intervals,
        undetermined={rename[k]: [rename[o] for o in v] for k, v in undetermined.items()},
        strain=_baseline_strain(base_space, base_space + spaces[0] + spaces[1], u, result),
    )
