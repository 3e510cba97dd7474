"""Fitting a static table: the model that maps calibrated unknowns and effect parameters to a
campaign's predicted channels, its least squares, and the leave-one-group-out refits that give
held-out predictions and jackknife intervals (docs/diagnosis.md, "Static tables")."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares

from pamkit._core import Effect, MuscleParams
from pamkit.diagnosis.coordinates import Coordinate, configure, effect_space, unknown_coordinate, with_unknowns
from pamkit.diagnosis.identify import identify
from pamkit.diagnosis.tables.kinds import CYCLIC, PREDICTED, Campaign, kind_of
from pamkit.io.experiment import Experiment, test_names
from pamkit.io.guards import ExperimentError
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


class Fitter:
    """Least squares of one model (unknowns plus its effects' parameters) on chosen rows."""

    def __init__(self, model: TableModel, channels, scales: dict[str, float], make_effects=()):
        self.model = model
        self.channels = channels
        self.scales = scales
        self.make_effects = list(make_effects)  # fresh effects per evaluation: folds run in threads
        self.effect_spaces = [effect_space(make()) for make in self.make_effects]
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

    def residual(self, x: np.ndarray, rows: np.ndarray) -> np.ndarray:
        try:
            predicted = self.predict(x, rows)
        except ValueError:
            # A trial outside the braid's range: a large, finite residual steers the search back.
            return np.full(sum(int(self.model.predicts[c][rows].sum()) for c in self.channels), 1e3)
        return np.concatenate(
            [
                (predicted[c] - self.model.columns[c][rows])[self.model.predicts[c][rows]] / self.scales[c]
                for c in self.channels
            ]
        )

    def fit(self, rows: np.ndarray, starts: list[np.ndarray]) -> np.ndarray:
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
            )
            if best is None or result.cost < best.cost:
                best = result
        return best.x

    def undetermined(self, x: np.ndarray, rows: np.ndarray, folds: list[np.ndarray]) -> dict[str, list[str]]:
        """The fitted values the table does not determine (identify.py), by name, each with those it
        trades against: numerically null directions of the Jacobian at `x` (central differences at
        JACOBIAN_STEP of each search interval), and any value that no held-out refit (`folds`)
        moved, which a jackknife would report with a zero-width interval."""
        lower = np.array([c.lower for c in self.space])
        upper = np.array([c.upper for c in self.space])
        at = self.residual(x, rows)
        columns = []
        for index, w in enumerate(upper - lower):
            step = np.zeros_like(x)
            step[index] = JACOBIAN_STEP * w
            # One-sided at an end of the search interval: beyond it the model may not exist.
            ahead = x[index] + step[index] <= upper[index]
            behind = x[index] - step[index] >= lower[index]
            high = self.residual(x + step, rows) if ahead else at
            low = self.residual(x - step, rows) if behind else at
            columns.append((high - low) / (JACOBIAN_STEP * (int(ahead) + int(behind))))
        found = identify(np.column_stack(columns), widths=False).trades_against(self.names())
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
) -> TableFit:
    """Fits on the `used` rows (not censored), from `starts` (by default the declared values and
    STARTS), and again without each group; censored rows are predicted, and held out as NaN."""
    fitter = Fitter(model, channels, scales, make_effects)
    x = fitter.fit(np.flatnonzero(used), starts if starts is not None else fitter.starts())
    labels = np.unique(groups[used])

    def leave_out(label):
        kept = np.flatnonzero((groups != label) & used)
        held = np.flatnonzero((groups == label) & used)
        x_fold = fitter.fit(kept, [x])
        return held, x_fold, fitter.predict(x_fold, held)

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
    )


def heldout_rmse(fit: TableFit, measured, channel: str, rows=None) -> float:
    """Over the rows held out (`rows` of them, if given); censored rows have none."""
    residual = fit.heldout[channel] - measured[channel]
    if rows is not None:
        residual = residual[rows]
    residual = residual[np.isfinite(residual)]
    return float(np.sqrt(np.mean(residual**2))) if residual.size else math.nan
