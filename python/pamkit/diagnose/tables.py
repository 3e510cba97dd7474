"""Diagnosis of static tables: isometric maps, isotonic tests of settled steps and
free-inflation tables, as DESIGN.md's experiment kinds describe them; their units and noise are
in table_kinds.py, their report in table_report.py.

A table has no time axis, so the units held out are its groups: the held lengths of a map
(leave one length out: does the model carry to a length it was not fitted on?), an isotonic
test's sweeps, the rows of a free-inflation table. The baseline is the model the file declares
with its `[calibrate]` unknowns fitted; each catalog effect that acts on a static table is fitted
with the same unknowns free (one yardstick) and scored by the held-out RMSE it leaves. The rules
of decide.py hold: a cause needs a significant gain (MIN_GAIN, 95 % interval above zero, over
held-out groups) and credible parameters (none at a search bound, none outside its plausible
range); `none` only within NONE_WITHIN_NOISE of the table's noise; otherwise `unexplained`.
"""

from __future__ import annotations

import hashlib
import math
import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass

import numpy as np
from scipy.optimize import least_squares

from pamkit._core import (
    BladderLaw,
    Effect,
    EffectCatalog,
    EffectStage,
    GasMode,
    MuscleParams,
    fiber_revolutions_for_braid_angle,
)
from pamkit.diagnose.decide import BOOTSTRAP_SAMPLES, MIN_GAIN, NONE_WITHIN_NOISE, findings
from pamkit.diagnose.model import Coordinate, configure, effect_space
from pamkit.diagnose.table_kinds import Campaign, campaign_of, noise_of, test_names
from pamkit.effects import catalog as builtin_catalog
from pamkit.experiment import BRAID_ANGLE_KEY, Experiment, ExperimentError, declared_value
from pamkit.simulate import muscle_params, simulate_table

# The channels each kind predicts, and how its rows are grouped for holding out.
PREDICTED = {"isometric_map": ("force_N",), "free_inflation": ("length_m", "diameter_m"), "isotonic": ("length_m",)}
CHANNEL_UNITS = {"force_N": "N", "length_m": "m", "diameter_m": "m"}
# [calibrate] names each test of a campaign has its own value of (the rest are shared).
PER_TEST = ("load_N",)
# Fewer held-out groups than this cannot say whether a model carries beyond its fitted rows.
MIN_GROUPS = 3
# Local least squares from the declared values, then from these points of each unknown's
# interval: the static force is not convex in a braid angle and a modulus together.
STARTS = (0.25, 0.75)
# Unknowns whose declared range spans more than this ratio are searched on a log scale.
LOG_SPAN = 20.0


@dataclass
class TableFit:
    """One fitted model of a table: the calibrated unknowns, the effect's parameters, and its
    predictions on every row (fitted on all rows) and held out (each group predicted by the
    model fitted without it)."""

    name: str
    effects: list[Effect]
    params: dict[str, float]
    coordinates: dict[str, tuple[Coordinate, float]]
    predicted: dict[str, np.ndarray]
    heldout: dict[str, np.ndarray]
    intervals: dict[str, tuple[float, float]]  # jackknife 95 % over held-out groups
    x: np.ndarray | None = None  # the fitted coordinates, to start a larger model from
    error: str | None = None


@dataclass
class TableCandidate:
    fit: TableFit
    gain: dict[str, float]
    gain_ci95: dict[str, tuple[float, float]]
    score: float  # mean held-out gain over the predicted channels
    significant: bool
    findings: list[dict]  # parameters at a bound or implausible

    @property
    def credible(self) -> bool:
        return not self.findings


@dataclass
class TableDiagnosis:
    campaign: Campaign
    channels: tuple[str, ...]
    noise: dict[str, float]
    baseline: TableFit
    candidates: list[TableCandidate]
    skipped: dict[str, str]
    cause: str
    reason: str
    extended: TableFit
    extended_candidate: TableCandidate | None
    warnings: list[dict]
    margins: dict[str, float]
    added: list[dict]  # effects beside the cause, each with its held-out gain over the cause alone

    @property
    def groups(self) -> np.ndarray:
        return self.campaign.groups


class TableModel:
    """Maps calibrated unknowns and effect parameters to a campaign's predicted channels."""

    def __init__(self, campaign: Campaign):
        self.campaign = campaign
        self.kind = campaign.kind
        self.columns = campaign.columns
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
        self.unknowns = [self._coordinate(name, bounds, e) for name, (bounds, e) in declared.items()]

    def unknown_of(self, name: str, experiment: Experiment) -> str:
        """The unknown's name: a test's own unknown (its load) carries the test's name in a campaign."""
        if name not in PER_TEST or len(self.campaign.experiments) == 1:
            return name
        index = next(i for i, e in enumerate(self.campaign.experiments) if e is experiment)
        return f"{name}[{self.test_names[index]}]"

    def _coordinate(self, name: str, bounds: tuple[float, float], experiment: Experiment) -> Coordinate:
        lower, upper = bounds
        field = name.split("[", 1)[0]
        declared = declared_value(field, experiment.build, experiment.bladder, experiment.load_N)
        start = declared if lower < declared < upper else 0.5 * (lower + upper)
        source = "the [calibrate] bounds the experiment file declares"
        if lower > 0 and upper / lower > LOG_SPAN:
            return Coordinate(
                name, math.log(lower), math.log(upper), math.log(start), math.exp, math.log, (lower, upper), source
            )
        return Coordinate(name, lower, upper, start, plausible=(lower, upper), source=source)

    @staticmethod
    def params(experiment: Experiment, values: dict[str, float]) -> MuscleParams:
        params = muscle_params(experiment)
        build = params.build
        for name, value in values.items():
            if name in type(build).fields():
                setattr(build, name, value)
        if BRAID_ANGLE_KEY in values:
            build.fiber_revolutions = fiber_revolutions_for_braid_angle(build, values[BRAID_ANGLE_KEY])
        params.build = build
        if "bladder.shear_modulus_Pa" in values:
            params.bladder = BladderLaw.neo_hookean(values["bladder.shear_modulus_Pa"])
        return params

    def predict(self, values: dict[str, float], effects: list[Effect], rows: np.ndarray) -> dict[str, np.ndarray]:
        out = {c: np.empty(len(rows)) for c in PREDICTED[self.kind]}
        for i, experiment in enumerate(self.campaign.experiments):
            mine = np.flatnonzero(self.campaign.test[rows] == i)
            if len(mine) == 0:
                continue
            local = rows[mine] - int(np.flatnonzero(self.campaign.test == i)[0])
            load = values.get(self.unknown_of("load_N", experiment))
            predicted = simulate_table(experiment, self.params(experiment, values), effects, local, load)
            for channel in out:
                out[channel][mine] = predicted[channel]
        return out


class _Fitter:
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
            return np.full(len(rows) * len(self.channels), 1e3)
        return np.concatenate([(predicted[c] - self.model.columns[c][rows]) / self.scales[c] for c in self.channels])

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

    def starts(self) -> list[np.ndarray]:
        declared = np.array([c.start for c in self.space])
        out = [declared]
        for fraction in STARTS:
            point = declared.copy()
            point[: len(self.model.unknowns)] = [c.lower + fraction * (c.upper - c.lower) for c in self.model.unknowns]
            out.append(point)
        return out


def _fit_table(
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
    fitter = _Fitter(model, channels, scales, make_effects)
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
    intervals = {}
    count = len(folds)
    for index, (key, c) in enumerate(zip(names, fitter.space)):
        values = np.array([float(c.value(x_fold[index])) for _, x_fold, _ in folds])
        spread = math.sqrt((count - 1) / count * float(np.sum((values - values.mean()) ** 2)))
        intervals[key] = (params[key] - 1.96 * spread, params[key] + 1.96 * spread)
    every = np.arange(len(groups))
    return TableFit(name, fitter.effects(x), params, coordinates, fitter.predict(x, every), heldout, intervals, x=x)


def heldout_rmse(fit: TableFit, measured, channel: str, rows=None) -> float:
    """Over the rows held out (`rows` of them, if given); censored rows have none."""
    residual = fit.heldout[channel] - measured[channel]
    if rows is not None:
        residual = residual[rows]
    residual = residual[np.isfinite(residual)]
    return float(np.sqrt(np.mean(residual**2))) if residual.size else math.nan


def _findings(fit: TableFit) -> list[dict]:
    """decide.py's findings (parameters at a search bound or implausible), as report rows."""
    return [asdict(f) for f in findings(fit)]


def _seed(columns: dict[str, np.ndarray]) -> int:
    """The bootstrap's seed, drawn from the data: the same tables give the same report."""
    digest = hashlib.sha256()
    for name in sorted(columns):
        digest.update(np.ascontiguousarray(columns[name], dtype="<f8").tobytes())
    return int.from_bytes(digest.digest()[:8], "little")


def _judge(
    fit: TableFit, baseline: TableFit, measured, channels, groups: np.ndarray, used: np.ndarray, seed: int
) -> TableCandidate:
    labels = np.unique(groups[used])
    index = [np.flatnonzero((groups == label) & used) for label in labels]
    rng = np.random.default_rng(seed)
    draws = rng.integers(0, len(labels), size=(BOOTSTRAP_SAMPLES, len(labels)))
    gain, ci = {}, {}
    for c in channels:
        base = [float(np.sum((baseline.heldout[c][rows] - measured[c][rows]) ** 2)) for rows in index]
        ext = [float(np.sum((fit.heldout[c][rows] - measured[c][rows]) ** 2)) for rows in index]
        base, ext = np.array(base), np.array(ext)
        gain[c] = 1.0 - math.sqrt(ext.sum() / base.sum()) if base.sum() > 0 else 0.0
        samples = 1.0 - np.sqrt(ext[draws].sum(axis=1) / np.maximum(base[draws].sum(axis=1), 1e-300))
        ci[c] = (float(np.quantile(samples, 0.025)), float(np.quantile(samples, 0.975)))
    score = float(np.mean([gain[c] for c in channels]))
    significant = all(gain[c] >= MIN_GAIN and ci[c][0] > 0.0 for c in channels)
    return TableCandidate(fit, gain, ci, score, significant, _findings(fit))


def static_candidates(catalog: EffectCatalog) -> tuple[list[str], dict[str, str]]:
    """The catalog's effects that can act on a static table (physical ones that act at supplied
    pressure, and errors of the transducer whose reading drives it), and why each other one
    cannot."""
    out, skipped = [], {}
    for name in catalog.names():
        effect = catalog.make(name)
        if effect.stage() != EffectStage.physics and not effect.reads_supplied_pressure():
            skipped[name] = "acts on the motion or the instruments over time; a table has no time axis"
            continue
        acts, why_not = effect.acts_in(GasMode.supplied)
        if not acts:
            skipped[name] = why_not
            continue
        out.append(name)
    return out, skipped


def diagnose_table(
    experiments: Experiment | list[Experiment],
    catalog: EffectCatalog | None = None,
    progress=None,
    threads: int | None = None,
) -> TableDiagnosis:
    """Calibrates the tables' unknowns, scores every static catalog effect on held-out groups,
    and decides. Several tables of one muscle form a campaign. Raises ExperimentError when there
    are too few groups to hold out."""
    progress = progress or (lambda message: None)
    campaign = campaign_of(experiments if isinstance(experiments, list) else [experiments])
    channels = PREDICTED[campaign.kind]
    groups, group_name = campaign.groups, campaign.group_name
    used = ~campaign.censored
    labels = np.unique(groups[used])
    if len(labels) < MIN_GROUPS:
        what = "measure the map at more held lengths" if campaign.kind == "isometric_map" else "add rows"
        raise ExperimentError(
            f"{campaign.name}: {len(labels)} {group_name}(s); holding out needs at least {MIN_GROUPS} ({what})"
        )
    model = TableModel(campaign)
    measured = {c: campaign.columns[c] for c in channels}
    noise = noise_of(campaign, channels)
    # Residuals of channels with different units are compared in units of their spread.
    scales = {c: float(np.std(measured[c][used])) or 1.0 for c in channels}
    seed = _seed(campaign.columns)
    catalog = catalog or builtin_catalog()
    names, skipped = static_candidates(catalog)
    unknowns = ", ".join(c.name for c in model.unknowns) or "nothing"
    with ThreadPoolExecutor(max_workers=threads or os.cpu_count() or 1) as pool:
        progress(f"calibrating {unknowns} on {len(groups)} rows, holding out each of {len(labels)} {group_name}s")
        if not used.all():
            progress(f"{int((~used).sum())} row(s) read the pressure transducer's range end: predicted, not scored")
        baseline = _fit_table("baseline", model, channels, scales, (), groups, used, pool)
        candidates = []
        for name in names:

            def make_effect(name=name):
                return catalog.make(name)

            start = _Fitter(model, channels, scales, [make_effect])
            x0 = start.starts()[0]
            # Probed away from its start, which may be the effect's neutral value (no offset).
            probe = x0.copy()
            for index, c in enumerate(start.effect_space, start=len(model.unknowns)):
                probe[index] = c.lower + 0.75 * (c.upper - c.lower)
            rows = np.arange(len(groups))
            try:
                with_effect = start.predict(probe, rows)
                without = _Fitter(model, channels, scales).predict(x0[: len(model.unknowns)], rows)
            except ValueError as error:
                skipped[name] = f"cannot be evaluated on this table: {error}"
                continue
            if all(np.array_equal(with_effect[c], without[c]) for c in channels):
                skipped[name] = "does not change a static table's prediction"
                continue
            progress(f"fitting {name}")
            fit = _fit_table(name, model, channels, scales, [make_effect], groups, used, pool)
            candidates.append(_judge(fit, baseline, measured, channels, groups, used, seed))
        candidates.sort(key=lambda j: -j.score)
        cause, reason, chosen, margins = _decide(candidates, baseline, measured, channels, noise)
        added = []
        significant = [j for j in candidates if j.significant]
        if significant:  # named, or not credible alone: a second effect may be what it lacks
            pair, added = _second_effect(significant[0], candidates, baseline, model, catalog, progress, pool, seed)
            if added:
                chosen, cause = pair, significant[0].fit.name
                margins["over_none"] = float(min(pair.gain_ci95[c][0] for c in channels))
                margins["added_over_cause"] = float(min(added[0]["gain_ci95"][c][0] for c in channels))
                reason = (
                    f"its held-out gain with {added[0]['effect']} beside it is significant, every parameter plausible"
                )
    extended = chosen.fit if chosen else baseline
    warnings = _findings(baseline) + (chosen.findings if chosen else [])
    return TableDiagnosis(
        campaign,
        channels,
        noise,
        baseline,
        candidates,
        skipped,
        cause,
        reason,
        extended,
        chosen,
        warnings,
        margins,
        added,
    )


def _second_effect(first, candidates, baseline, model, catalog, progress, pool, seed):
    """A second effect beside the best significant candidate `first`: each other candidate is
    fitted jointly with it (from its fit), and the best pair is kept when it gains significantly
    on held-out groups over `first` alone and over the baseline, with every parameter credible.
    A real rig has more than one thing wrong (a hysteresis and a transducer's offset): one name
    cannot hold both, and `first` alone may fit only with a parameter at a bound. Returns the
    pair judged against the baseline and what was added, with its gain over `first` alone; or
    `first` and nothing."""
    campaign, channels = model.campaign, PREDICTED[model.kind]
    measured = {c: campaign.columns[c] for c in channels}
    used = ~campaign.censored
    scales = {c: float(np.std(measured[c][used])) or 1.0 for c in channels}
    best = None
    for other in candidates:
        if other is first:
            continue
        names = [first.fit.name, other.fit.name]
        makes = [lambda n=n: catalog.make(n) for n in names]
        fitter = _Fitter(model, channels, scales, makes)
        start = np.concatenate([first.fit.x, [c.start for c in fitter.effect_spaces[1]]])
        progress(f"fitting {names[1]} beside {names[0]}")
        pair = _fit_table(" + ".join(names), model, channels, scales, makes, campaign.groups, used, pool, [start])
        over_cause = _judge(pair, first.fit, measured, channels, campaign.groups, used, seed)
        if over_cause.significant and over_cause.credible and (best is None or over_cause.score > best.score):
            best = over_cause
    if best is None:
        return first, []
    pair = _judge(best.fit, baseline, measured, channels, campaign.groups, used, seed)
    if not (pair.significant and pair.credible):
        return first, []
    effect = best.fit.effects[1].name()
    return pair, [{"effect": effect, "gain": best.gain, "gain_ci95": {c: list(v) for c, v in best.gain_ci95.items()}}]


def _decide(candidates, baseline, measured, channels, noise):
    significant = [j for j in candidates if j.significant]
    margins: dict[str, float] = {}
    if significant:
        best = significant[0]
        if not best.credible:
            what = "; ".join(
                f"{f['parameter']} = {f['value']:.4g}"
                + (f" at its search bound {f['bound']:.4g}" if f["bound"] else "")
                for f in best.findings
            )
            return "unexplained", f"the best candidate, {best.fit.name}, fits only with {what}", None, margins
        runner = next((j for j in candidates if j is not best), None)
        margins["over_none"] = float(min(best.gain_ci95[c][0] for c in channels))
        if runner is not None:
            margins["over_runner_up"] = float(best.score - runner.score)
        return best.fit.name, "its held-out gain is significant and its parameters plausible", best, margins
    ratios = {c: heldout_rmse(baseline, measured, c) / noise[c] for c in channels if noise[c] > 0}
    if ratios and max(ratios.values()) <= NONE_WITHIN_NOISE:
        margins["within_noise"] = float(NONE_WITHIN_NOISE - max(ratios.values()))
        return "none", "the calibrated model carries to held-out groups within the noise", None, margins
    left = ", ".join(f"{c} at {r:.1f}x its noise" for c, r in ratios.items())
    return "unexplained", f"no catalog effect gains significantly; held-out error left: {left}", None, margins
