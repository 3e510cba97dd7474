"""Fitting a static table: the model that maps calibrated unknowns and effect parameters to a
campaign's predicted channels, its least squares, and the leave-one-group-out refits that give
held-out predictions and jackknife intervals (docs/diagnosis.md, "Static tables")."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares

from pamkit._core import Effect, MuscleParams
from pamkit.diagnosis.coordinates import (
    Coordinate,
    configure,
    effect_space,
    uncertain_coordinate,
    uncertain_fields,
    unknown_coordinate,
    with_unknowns,
)
from pamkit.diagnosis.identify import identify
from pamkit.diagnosis.tables.kinds import CYCLIC, PREDICTED, Campaign, kind_of
from pamkit.io.experiment import Experiment, test_names
from pamkit.io.guards import ExperimentError
from pamkit.io.sections import BRAID_ANGLE_KEY
from pamkit.simulation import muscle_params, simulate_experiment, simulate_table

# [calibrate] names each test of a campaign has its own value of (the rest are shared).
PER_TEST = ("load_N",)
# Local least squares from the declared values, then from these points of each unknown's
# interval: the static force is not convex in a braid angle and a modulus together.
STARTS = (0.25, 0.75)
# Central differences at this share of each search interval tell whether the table depends on it.
JACOBIAN_STEP = 1e-5
# A jackknife spread below this share of the search interval is no spread: the refits did not move.
SAME = 1e-6
# A fit from another start replaces the whole fit where its cost is lower by more than this share:
# least squares stopped at a relative change of 1e-8 leave the same minimum within it.
BETTER = 1e-6
# Steps of the whole fit from a refit's solution before it is kept or dropped: each costs one
# evaluation of every row and, for the next, one Jacobian.
PROBE_STEPS = 3


@dataclass
class TableFit:
    """One fitted model of a table: the calibrated unknowns, the effect's parameters, and its
    predictions on every row (fitted on all rows) and held out (each group predicted by the
    model fitted without it)."""

    name: str
    effects: list[Effect]
    params: dict[str, float]
    coordinates: dict[str, tuple[Coordinate, float]]
    predicted: dict[str, np.ndarray]  # NaN on rows whose kind does not predict the channel
    heldout: dict[str, np.ndarray]
    intervals: dict[str, tuple[float, float]]  # jackknife 95 % over held-out groups
    x: np.ndarray | None = None  # the fitted coordinates, to start a larger model from
    error: str | None = None
    # the values the table does not determine, each with those it trades against (identify.py)
    undetermined: dict[str, list[str]] = field(default_factory=dict)
    # held-out groups, by index, whose prediction rests on values only they determine (rests_on)
    rests_on: dict[int, list[str]] = field(default_factory=dict)


class TableModel:
    """Maps calibrated unknowns and effect parameters to a campaign's predicted channels."""

    def __init__(self, campaign: Campaign):
        self.campaign = campaign
        self.kind = campaign.kind
        self.channels = campaign.channels
        self.columns = campaign.columns
        self.predicts = {c: campaign.predicts(c) for c in self.channels}
        self.test_names = test_names(campaign.experiments)
        declared: dict[str, tuple[tuple[float, float], Experiment]] = {}
        for e in campaign.experiments:
            for name, bounds in e.calibrate.items():
                if name in PER_TEST:
                    declared[self.unknown_of(name, e)] = (bounds, e)
                    continue
                if name in declared and declared[name][0] != bounds:
                    raise ExperimentError(
                        f"{e.path}: [calibrate] {name} = {list(bounds)} differs from {list(declared[name][0])} in "
                        f"{declared[name][1].path}: a campaign shares its unknowns"
                    )
                declared.setdefault(name, (bounds, e))
        self.unknowns = [unknown_coordinate(name, bounds, e) for name, (bounds, e) in declared.items()]
        self.unknowns += self._uncertain(set(declared))

    def _uncertain(self, calibrated: set[str]) -> list[Coordinate]:
        """The build fields a file's own [uncertain] frees within its tolerance, beside the
        [calibrate] unknowns (not the default wind a file without the section gets: a table's
        build is what its file declares). A campaign shares them, so its tests must agree."""
        if {"fiber_revolutions", BRAID_ANGLE_KEY} & calibrated:  # one number: calibrated, it is not uncertain
            calibrated = calibrated | {"fiber_revolutions", BRAID_ANGLE_KEY}
        out: dict[str, tuple[Coordinate, Experiment]] = {}
        for e in self.campaign.experiments:
            if not e.uncertain_declared:
                continue
            for name in uncertain_fields(e):
                if name in calibrated:
                    continue
                coordinate = uncertain_coordinate(name, e)
                if name in out and (out[name][0].lower, out[name][0].upper) != (coordinate.lower, coordinate.upper):
                    raise ExperimentError(
                        f"{e.path}: [uncertain] {name} gives {coordinate.lower:g} to {coordinate.upper:g}, "
                        f"{out[name][1].path} {out[name][0].lower:g} to {out[name][0].upper:g}: a campaign shares "
                        "its build"
                    )
                out.setdefault(name, (coordinate, e))
        return [coordinate for coordinate, _ in out.values()]

    def unknown_of(self, name: str, experiment: Experiment) -> str:
        """The unknown's name: a test's own unknown (its load) carries the test's name in a campaign."""
        if name not in PER_TEST or len(self.campaign.experiments) == 1:
            return name
        index = next(i for i, e in enumerate(self.campaign.experiments) if e is experiment)
        return f"{name}[{self.test_names[index]}]"

    @staticmethod
    def params(experiment: Experiment, values: dict[str, float]) -> MuscleParams:
        return with_unknowns(muscle_params(experiment), values)

    def predict(self, values: dict[str, float], effects: list[Effect], rows: np.ndarray) -> dict[str, np.ndarray]:
        """Each channel at `rows`; NaN where the row's kind does not predict it."""
        out = {c: np.full(len(rows), np.nan) for c in self.channels}
        for i, experiment in enumerate(self.campaign.experiments):
            mine = np.flatnonzero(self.campaign.test[rows] == i)
            if len(mine) == 0:
                continue
            local = rows[mine] - int(np.flatnonzero(self.campaign.test == i)[0])
            kind = kind_of(experiment)
            if kind == CYCLIC:  # one record: every sample is simulated, the rows asked for returned
                series = simulate_experiment(experiment, self.params(experiment, values), effects=effects)
                predicted = {channel: series[channel][local] for channel in PREDICTED[kind]}
            else:
                load = values.get(self.unknown_of("load_N", experiment))
                predicted = simulate_table(experiment, self.params(experiment, values), effects, local, load)
            for channel in PREDICTED[kind]:
                out[channel][mine] = predicted[channel]
        return out


# Effect parameters a static table cannot tell from the muscle's build, held at their neutral
# values. The gain of the transducer whose reading drives the model scales the gas's force,
# -p dV/dL, exactly as the muscle's area does, and nearly as its braid angle does (on an
# independent DMSP map read 10 kPa high, the gain fitted 0.65 beside the braid angle and the
# transducer was refused, on 6 seeds of 6); its offset shifts each held length's line in pressure,
# which no build can.
HELD_IN_TABLES = {"sensor_offset": ("gain",)}


def table_space(effect: Effect) -> list[Coordinate]:
    """An effect's fit coordinates in a table: effect_space's, less HELD_IN_TABLES."""
    held = HELD_IN_TABLES.get(effect.name(), ())
    return [c for c in effect_space(effect) if c.name not in held]


class Fitter:
    """Least squares of one model (unknowns plus its effects' parameters) on chosen rows."""

    def __init__(self, model: TableModel, channels, scales: dict[str, float], make_effects=()):
        self.model = model
        self.channels = channels
        self.scales = scales
        self.make_effects = list(make_effects)  # fresh effects per evaluation: folds run in threads
        self.effect_spaces = [table_space(make()) for make in self.make_effects]
        self.effect_space = [c for space in self.effect_spaces for c in space]
        self.space = model.unknowns + self.effect_space

    def values(self, x: np.ndarray) -> dict[str, float]:
        return {c.name: float(c.value(v)) for c, v in zip(self.model.unknowns, x)}

    def effects(self, x: np.ndarray) -> list[Effect]:
        out, start = [], len(self.model.unknowns)
        for make, space in zip(self.make_effects, self.effect_spaces):
            out.append(configure(make(), space, x[start : start + len(space)]))
            start += len(space)
        return out

    def names(self) -> list[str]:
        """Each coordinate's name in a report: an effect's own when it is alone, else prefixed."""
        if len(self.make_effects) < 2:
            return [c.name for c in self.space]
        prefixed = [
            f"{make().name()}.{c.name}" for make, space in zip(self.make_effects, self.effect_spaces) for c in space
        ]
        return [c.name for c in self.model.unknowns] + prefixed

    def predict(self, x: np.ndarray, rows: np.ndarray) -> dict[str, np.ndarray]:
        return self.model.predict(self.values(x), self.effects(x), rows)

    def residual(self, x: np.ndarray, rows: np.ndarray, scales: dict[str, float] | None = None) -> np.ndarray:
        """Each channel's residual at `rows` over its scale (by default the fit's: the channel's spread)."""
        scales = scales or self.scales
        try:
            predicted = self.predict(x, rows)
        except ValueError:
            # A trial outside the braid's range: a large, finite residual steers the search back.
            return np.full(sum(int(self.model.predicts[c][rows].sum()) for c in self.channels), 1e3)
        return np.concatenate(
            [
                (predicted[c] - self.model.columns[c][rows])[self.model.predicts[c][rows]] / scales[c]
                for c in self.channels
            ]
        )

    def cost(self, x: np.ndarray, rows: np.ndarray) -> float:
        return 0.5 * float(np.sum(self.residual(x, rows) ** 2))

    def entry_rows(self, rows: np.ndarray) -> np.ndarray:
        """The row of each entry of `residual(x, rows)`: each channel's predicted rows in turn."""
        return np.concatenate([rows[self.model.predicts[c][rows]] for c in self.channels])

    def jacobian(self, x: np.ndarray, rows: np.ndarray, scales: dict[str, float] | None = None) -> np.ndarray:
        """d residual / d coordinate at `x` over the unit box (central differences at JACOBIAN_STEP of
        each search interval; one-sided at an end of it, beyond which the model may not exist)."""
        lower = np.array([c.lower for c in self.space])
        upper = np.array([c.upper for c in self.space])
        at = self.residual(x, rows, scales)
        columns = []
        for index, w in enumerate(upper - lower):
            step = np.zeros_like(x)
            step[index] = JACOBIAN_STEP * w
            ahead = x[index] + step[index] <= upper[index]
            behind = x[index] - step[index] >= lower[index]
            high = self.residual(x + step, rows, scales) if ahead else at
            low = self.residual(x - step, rows, scales) if behind else at
            columns.append((high - low) / (JACOBIAN_STEP * (int(ahead) + int(behind))))
        return np.column_stack(columns) if columns else np.zeros((at.size, 0))

    def fit(self, rows: np.ndarray, starts: list[np.ndarray], steps: int | None = None) -> np.ndarray:
        """Least squares on `rows` from each of `starts`, the best kept; `steps` caps each search's
        evaluations of the residual (its Jacobian's aside)."""
        if not self.space:
            return np.array([])
        lower = np.array([c.lower for c in self.space])
        upper = np.array([c.upper for c in self.space])
        best = None
        for x0 in starts:
            result = least_squares(
                lambda x: self.residual(x, rows),
                np.clip(x0, lower, upper),
                bounds=(lower, upper),
                x_scale=upper - lower,
                diff_step=1e-6,
                max_nfev=steps,
            )
            if best is None or result.cost < best.cost:
                best = result
        return best.x

    def undetermined(self, x: np.ndarray, rows: np.ndarray, folds: list[np.ndarray]) -> dict[str, list[str]]:
        """The fitted values the table does not determine (identify.py), by name, each with those it
        trades against: numerically null directions of the Jacobian at `x` (central differences at
        JACOBIAN_STEP of each search interval), and any value that no held-out refit (`folds`)
        moved, which a jackknife would report with a zero-width interval."""
        found = identify(self.jacobian(x, rows), widths=False).trades_against(self.names())
        names = self.names()
        for index, name in enumerate(names):
            if folds and all(fold[index] == x[index] for fold in folds) and name not in found:
                found[name] = []
        return found

    def starts(self) -> list[np.ndarray]:
        declared = np.array([c.start for c in self.space])
        out = [declared]
        for fraction in STARTS:
            point = declared.copy()
            point[: len(self.model.unknowns)] = [c.lower + fraction * (c.upper - c.lower) for c in self.model.unknowns]
            out.append(point)
        return out


def fit_table(
    name: str,
    model: TableModel,
    channels,
    scales,
    make_effects,
    groups: np.ndarray,
    used: np.ndarray,
    pool,
    starts=None,
    noise: dict[str, float] | None = None,
) -> TableFit:
    """Fits on the `used` rows (not censored), from `starts` (by default the declared values and
    STARTS) and, where it fits better, from the refit without one group that improved most on its
    own rows; and again without each group. Censored rows are predicted, and held out as NaN. With
    the channels' `noise`, finds the groups whose held-out prediction rests on values only they
    determine (rests_on)."""
    fitter = Fitter(model, channels, scales, make_effects)
    rows = np.flatnonzero(used)
    x = fitter.fit(rows, starts if starts is not None else fitter.starts())
    labels = np.unique(groups[used])

    def leave_out(label):
        kept = np.flatnonzero((groups != label) & used)
        held = np.flatnonzero((groups == label) & used)
        x_fold = fitter.fit(kept, [x])
        return held, x_fold, fitter.predict(x_fold, held)

    folds = list(pool.map(leave_out, labels))
    # The refit that improved most on the whole fit over its own rows may have found a basin the
    # whole fit's starts missed (a friction's break-away distance that only some groups bear
    # on): a few steps of the whole fit from there tell, and where they already fit every row
    # better than the whole fit by more than the least squares' own tolerance, the whole fit goes
    # on from there and its folds start from the new fit.
    at_x = fitter.residual(x, rows) ** 2  # the whole fit's squares, each fold's kept rows among them
    entries = fitter.entry_rows(rows)
    deepest = min(folds, key=lambda fold: _fold_drop(fitter, at_x, entries, fold, rows))[1]
    probe = fitter.fit(rows, [deepest], steps=PROBE_STEPS)
    if fitter.cost(probe, rows) < (1.0 - BETTER) * fitter.cost(x, rows):
        x = fitter.fit(rows, [probe])
        folds = list(pool.map(leave_out, labels))
    heldout = {c: np.full(len(groups), np.nan) for c in channels}
    for held, _, predicted in folds:
        for c in channels:
            heldout[c][held] = predicted[c]
    names = fitter.names()
    coordinates = {key: (c, float(v)) for key, c, v in zip(names, fitter.space, x)}
    params = {key: float(c.value(v)) for key, c, v in zip(names, fitter.space, x)}
    undetermined = fitter.undetermined(x, np.flatnonzero(used), [x_fold for _, x_fold, _ in folds])
    intervals = {}
    count = len(folds)
    for index, (key, c) in enumerate(zip(names, fitter.space)):
        if names[index] in undetermined:  # its whole search interval, never a zero width
            intervals[key] = tuple(sorted((float(c.value(c.lower)), float(c.value(c.upper)))))
            continue
        values = np.array([float(c.value(x_fold[index])) for _, x_fold, _ in folds])
        spread = math.sqrt((count - 1) / count * float(np.sum((values - values.mean()) ** 2)))
        box = abs(float(c.value(c.upper)) - float(c.value(c.lower)))
        if 1.96 * spread < SAME * box:
            # Every held-out refit ended where the whole fit did (a bound holds it there): the
            # jackknife cannot tell how far the data would take it.
            undetermined[key] = []
            intervals[key] = tuple(sorted((float(c.value(c.lower)), float(c.value(c.upper)))))
            continue
        intervals[key] = (params[key] - 1.96 * spread, params[key] + 1.96 * spread)
    every = np.arange(len(groups))
    return TableFit(
        name,
        fitter.effects(x),
        params,
        coordinates,
        fitter.predict(x, every),
        heldout,
        intervals,
        x=x,
        undetermined=undetermined,
        rests_on=rests_on(fitter, x, groups, used, noise, undetermined) if noise else {},
    )


def rests_on(
    fitter: Fitter,
    x: np.ndarray,
    groups: np.ndarray,
    used: np.ndarray,
    noise: dict[str, float],
    undetermined: dict[str, list[str]],
) -> dict[int, list[str]]:
    """The held-out groups, by index, predicted with values the whole table determines but the
    other groups alone do not, each with those values: held out, such a group is predicted with
    what its refit could not tell (a friction's break-away distance where only one held length
    contracts less than it), and its error is the experiment's design, not a test of the model.
    Linearised at the whole fit, where the values are known (a refit without the group may have
    wandered to where nothing depends on them): a value is undetermined by the other groups as
    identify() finds it with residuals in units of the noise, and the group's prediction depends
    on it when crossing its search interval moves it by more than the noise (root mean square over
    the group's rows)."""
    if not fitter.space or not all(noise[c] > 0 for c in fitter.channels):
        return {}
    rows = np.flatnonzero(used)
    jacobian = fitter.jacobian(x, rows, noise)
    entry_rows = fitter.entry_rows(rows)
    names = fitter.names()
    out = {}
    for label in np.unique(groups[used]):
        mine = groups[entry_rows] == label
        open_without = identify(jacobian[~mine]).undetermined
        moves = jacobian[mine]
        values = [
            names[j]
            for j in sorted(open_without)
            if names[j] not in undetermined and np.sqrt(np.mean(moves[:, j] ** 2)) > 1.0
        ]
        if values:
            out[int(label)] = values
    return out


def _fold_drop(fitter: Fitter, at_x: np.ndarray, entries: np.ndarray, fold, rows: np.ndarray) -> float:
    """A fold's cost over the rows it kept, as a share of the whole fit's cost there (`at_x`: the
    whole fit's squared residual on `rows`, entry by entry; `entries`: the row of each)."""
    held, x_fold, _ = fold
    before = 0.5 * float(np.sum(at_x[~np.isin(entries, held)]))
    return fitter.cost(x_fold, rows[~np.isin(rows, held)]) / before if before > 0 else 1.0


def heldout_rmse(fit: TableFit, measured, channel: str, rows=None) -> float:
    """Over the rows held out (`rows` of them, if given); censored rows have none."""
    residual = fit.heldout[channel] - measured[channel]
    if rows is not None:
        residual = residual[rows]
    residual = residual[np.isfinite(residual)]
    return float(np.sqrt(np.mean(residual**2))) if residual.size else math.nan
