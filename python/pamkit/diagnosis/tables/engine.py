"""Diagnosis of static tables: isometric maps, isotonic tests of settled steps and
free-inflation tables, the kinds docs/experiments.md describes, and beside them a supplied time
series of the same muscle (a cyclic test); their units and noise are in kinds.py, their fits in
fit.py, the search of what is left in discover.py and where it lies in remainder.py, their report
in report.py (all in this package).

A table has no time axis, so the units held out are its groups: the held lengths of a map
(leave one length out: does the model carry to a length it was not fitted on?), an isotonic
test's sweeps, the rows of a free-inflation table, a cyclic test's stretch cycles. A campaign's
tests are also each predicted by the model calibrated on the others alone (heldout_by_test).
The baseline is the model the file declares with its `[calibrate]` unknowns fitted; each catalog
effect that acts on a static table is fitted with the same unknowns free (one yardstick) and
scored by the held-out RMSE it leaves. The rules of series/decide.py hold: a cause needs a significant
gain (MIN_GAIN, 95 % interval above zero, over held-out groups) and credible parameters (none at
a search bound, none outside its plausible range); `none` only within NONE_WITHIN_NOISE of the
table's noise; otherwise `unexplained`.
"""

from __future__ import annotations

import hashlib
import math
import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass, field

import numpy as np

from pamkit._core import EffectCatalog, EffectStage, GasMode
from pamkit.diagnosis.coordinates import findings
from pamkit.diagnosis.significance import BOOTSTRAP_SAMPLES, MIN_GAIN, NONE_WITHIN_NOISE
from pamkit.diagnosis.supply import VACUUM_TOLERANCE_PA, implied_vacuum
from pamkit.diagnosis.tables.discover import discover_table
from pamkit.diagnosis.tables.fit import Fitter, TableFit, TableModel, fit_table, heldout_rmse
from pamkit.diagnosis.tables.kinds import MIN_GROUPS, Campaign, beyond_reach, campaign_of, noise_of
from pamkit.diagnosis.tables.remainder import where_left
from pamkit.effects import catalog as builtin_catalog
from pamkit.io.columns import value_from_si
from pamkit.io.experiment import Experiment, test_names
from pamkit.io.guards import ExperimentError


@dataclass
class TableCandidate:
    fit: TableFit
    gain: dict[str, float]  # on the held-out rows
    gain_ci95: dict[str, tuple[float, float]]
    score: float  # mean held-out gain over the predicted channels, where the effect acts
    significant: bool
    findings: list[dict]  # its parameters at a bound or implausible (and those it moved there)
    strain: list[dict] = field(default_factory=list)  # the calibrated baseline's findings it shares
    # an effect between the branches: its gain on what differs between them, where it is judged
    between: dict | None = None
    # held-out groups left out of its judgement: each predicted, by it or the model it is judged
    # against, with values only that group determines (TableFit.rests_on), by the group's label
    untested: dict[str, list[str]] = field(default_factory=dict)
    # the score on each bootstrap draw of the held-out groups (the same draws for every candidate)
    samples: np.ndarray = field(default_factory=lambda: np.zeros(0))

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
    discovered_by_channel: dict[str, dict]  # what is left, per channel beyond its noise
    remainder: dict[str, float]  # held-out RMSE over noise of each channel still above NONE_WITHIN_NOISE
    # a campaign's tests, each predicted by the model fitted on the others (heldout_by_test)
    by_test: dict[str, dict] = field(default_factory=dict)
    # where each remainder channel's error lies (where_left)
    remainder_where: dict[str, dict] = field(default_factory=dict)

    @property
    def discovered(self) -> dict:
        """The report's `discovered` (docs/reference/report.md): the terms of the channel furthest above its noise."""
        return next(iter(self.discovered_by_channel.values()), {})

    @property
    def groups(self) -> np.ndarray:
        return self.campaign.groups


def _findings(fit: TableFit) -> list[dict]:
    """coordinates.py's findings (parameters at a search bound or implausible), as report rows."""
    return [asdict(f) for f in findings(fit)]


def _vacuum(fit: TableFit, campaign: Campaign) -> list[dict]:
    """A transducer's error that would have the muscle hold a vacuum where a row was read
    (supply.implied_vacuum), as a report row beside the parameters' findings."""
    out = []
    for i, experiment in enumerate(campaign.experiments):
        rows = np.flatnonzero((campaign.test == i) & ~campaign.censored)
        reading = campaign.columns["gauge_pressure_Pa"][rows]
        found = implied_vacuum(fit.effects, [], reading)
        if found is None:
            continue
        row, true_Pa = found
        out.append(
            {
                "parameter": "lowest_true_gauge_Pa",
                "value": true_Pa,
                "bound": None,
                "plausible": [-VACUUM_TOLERANCE_PA, None],
                "source": (
                    f"{experiment.path}: where the transducer read "
                    f"{value_from_si('gauge_pressure_Pa', reading[row]):g} kPa the muscle would have held a vacuum; "
                    "a regulator supplies air or vents it, never a vacuum"
                ),
                "beyond": None,
                "rmse_drop": None,
            }
        )
    return out


def _seed(columns: dict[str, np.ndarray]) -> int:
    """The bootstrap's seed, drawn from the data: the same tables give the same report."""
    digest = hashlib.sha256()
    for name in sorted(columns):
        digest.update(np.ascontiguousarray(columns[name], dtype="<f8").tobytes())
    return int.from_bytes(digest.digest()[:8], "little")


def branch_difference(residual: np.ndarray, pressure: np.ndarray, branch: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """What differs between a group's two branches: at each venting row, its residual less the
    pressurising branch's interpolated at the same pressure (rows where the branches overlap). An
    effect between the branches (a hysteresis) acts on this, not on the branches' mean."""
    up, down = rows[branch[rows] > 0], rows[branch[rows] < 0]
    if up.size < 2 or down.size < 1:
        return np.zeros(0)
    order = np.argsort(pressure[up])
    p_up, r_up = pressure[up][order], residual[up][order]
    inside = down[(pressure[down] >= p_up[0]) & (pressure[down] <= p_up[-1])]
    return residual[inside] - np.interp(pressure[inside], p_up, r_up)


def _squares(residual: np.ndarray) -> float:
    """A group's sum of squared residuals; NaN (a row of a kind that does not predict the channel)
    adds nothing."""
    return float(np.nansum(residual**2))


def _gains(base: np.ndarray, ext: np.ndarray, draws: np.ndarray) -> tuple[float, tuple[float, float], np.ndarray]:
    """Held-out gain from per-group sums of squares, its bootstrap interval over groups and the
    gain on each draw."""
    gain = 1.0 - math.sqrt(ext.sum() / base.sum()) if base.sum() > 0 else 0.0
    samples = 1.0 - np.sqrt(ext[draws].sum(axis=1) / np.maximum(base[draws].sum(axis=1), 1e-300))
    return gain, (float(np.quantile(samples, 0.025)), float(np.quantile(samples, 0.975))), samples


def _judge(
    fit: TableFit,
    baseline: TableFit,
    measured,
    channels,
    groups: np.ndarray,
    used: np.ndarray,
    seed: int,
    campaign: Campaign | None = None,
    calibrated: list[dict] | None = None,
    acting=None,
) -> TableCandidate:
    """`fit` scored on held-out groups against `baseline`. An effect that shows only between the
    pressurising and venting branches is judged on what differs between them (branch_difference),
    where it acts; its gain on the rows themselves is reported beside. A finding the calibrated
    baseline has too (`calibrated`: its parameters at a bound or implausible) is the base model's
    strain, not held against the candidate, unless the candidate is an instrument that would then
    correct the table it alone predicts. `acting` are the effects whose gain this is (by default all
    of `fit`'s; a second effect judged beside a first: that one). A group that either model
    predicts with values only that group determines (TableFit.rests_on) tests neither: it is left
    out of the judgement, and said so (`untested`), while MIN_GROUPS groups are left to judge on;
    with fewer, every group is judged, as a table of so few groups would be."""
    untestable = {**baseline.rests_on, **fit.rests_on}
    labels = np.unique(groups[used])
    tested = np.array([label for label in labels if int(label) not in untestable])
    if len(tested) >= MIN_GROUPS:
        labels = tested
    else:
        untestable = {}
    index = [np.flatnonzero((groups == label) & used) for label in labels]
    rng = np.random.default_rng(seed)
    draws = rng.integers(0, len(labels), size=(BOOTSTRAP_SAMPLES, len(labels)))
    gain, ci, samples = {}, {}, {}
    for c in channels:
        base = np.array([_squares(baseline.heldout[c][rows] - measured[c][rows]) for rows in index])
        ext = np.array([_squares(fit.heldout[c][rows] - measured[c][rows]) for rows in index])
        gain[c], ci[c], samples[c] = _gains(base, ext, draws)
    between = campaign is not None and any(e.shows_between_branches() for e in (acting or fit.effects))
    judged_gain, judged_ci = gain, ci
    if between:
        pressure, branch = campaign.columns["gauge_pressure_Pa"], campaign.branch
        judged_gain, judged_ci, samples = {}, {}, {}
        for c in channels:
            r_base, r_fit = baseline.heldout[c] - measured[c], fit.heldout[c] - measured[c]
            base = np.array([_squares(branch_difference(r_base, pressure, branch, rows)) for rows in index])
            ext = np.array([_squares(branch_difference(r_fit, pressure, branch, rows)) for rows in index])
            judged_gain[c], judged_ci[c], samples[c] = _gains(base, ext, draws)
    score = float(np.mean([judged_gain[c] for c in channels]))
    significant = all(judged_gain[c] >= MIN_GAIN and judged_ci[c][0] > 0.0 for c in channels)
    own, strain = [], []
    corrector = all(e.stage() != EffectStage.physics for e in fit.effects)
    for finding in _findings(fit) + (_vacuum(fit, campaign) if campaign is not None else []):
        inherited = calibrated is not None and any(
            finding["parameter"] == f["parameter"] and finding["bound"] == f["bound"] for f in calibrated
        )
        (strain if inherited and not corrector else own).append(finding)
    names = campaign.group_labels if campaign is not None else [str(label) for label in range(groups.max() + 1)]
    untested = {names[label]: values for label, values in sorted(untestable.items())}
    candidate = TableCandidate(
        fit,
        gain,
        ci,
        score,
        significant,
        own,
        strain,
        untested=untested,
        samples=np.mean(list(samples.values()), axis=0),
    )
    if between:
        candidate.between = {"gain": judged_gain, "gain_ci95": {c: list(v) for c, v in judged_ci.items()}}
    return candidate


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
    channels = campaign.channels
    groups, group_name = campaign.groups, campaign.group_name
    used = ~campaign.censored
    labels = np.unique(groups[used])
    if len(labels) < MIN_GROUPS:
        what = (
            "measure the map at more held lengths, or pressurise and vent it again"
            if campaign.kind == "isometric_map"
            else "add rows"
        )
        raise ExperimentError(
            f"{campaign.name}: {len(labels)} {group_name}(s); holding out needs at least {MIN_GROUPS} ({what})"
        )
    model = TableModel(campaign)
    measured = {c: campaign.columns[c] for c in channels}
    noise = noise_of(campaign, channels)
    # Residuals of channels with different units are compared in units of their spread.
    scales = {c: float(np.std(measured[c][used & campaign.predicts(c)])) or 1.0 for c in channels}
    seed = _seed(campaign.columns)
    catalog = catalog or builtin_catalog()
    names, skipped = static_candidates(catalog)
    unknowns = ", ".join(c.name for c in model.unknowns) or "nothing"
    with ThreadPoolExecutor(max_workers=threads or os.cpu_count() or 1) as pool:
        progress(f"calibrating {unknowns} on {len(groups)} rows, holding out each of {len(labels)} {group_name}s")
        if not used.all():
            progress(f"{int((~used).sum())} row(s) read the pressure transducer's range end: predicted, not scored")
        baseline = fit_table("baseline", model, channels, scales, (), groups, used, pool, noise=noise)
        candidates = []
        for name in names:
            if catalog.make(name).shows_between_branches() and not np.any(campaign.branch[used] < 0):
                skipped[name] = "shows only between pressurising and venting; this table has no venting rows"
                continue

            def make_effect(name=name):
                return catalog.make(name)

            start = Fitter(model, channels, scales, [make_effect])
            x0 = start.starts()[0]
            # Probed away from its start, which may be the effect's neutral value (no offset).
            probe = x0.copy()
            for index, c in enumerate(start.effect_space, start=len(model.unknowns)):
                probe[index] = c.lower + 0.75 * (c.upper - c.lower)
            rows = np.arange(len(groups))
            try:
                with_effect = start.predict(probe, rows)
                without = Fitter(model, channels, scales).predict(x0[: len(model.unknowns)], rows)
            except ValueError as error:
                skipped[name] = f"cannot be evaluated on this table: {error}"
                continue
            if all(np.array_equal(with_effect[c], without[c], equal_nan=True) for c in channels):
                skipped[name] = "does not change a static table's prediction"
                continue
            progress(f"fitting {name}")
            fit = fit_table(name, model, channels, scales, [make_effect], groups, used, pool, noise=noise)
            candidates.append(
                _judge(fit, baseline, measured, channels, groups, used, seed, campaign, _findings(baseline))
            )
        candidates.sort(key=lambda j: -j.score)
        cause, reason, chosen, margins = _decide(candidates, baseline, measured, channels, noise)
        added = []
        significant = [j for j in candidates if j.significant]
        if significant:  # named, or not credible alone: a second effect may be what it lacks
            pair, added = _second_effect(
                significant[0], candidates, baseline, model, catalog, progress, pool, seed, noise
            )
            if added:
                chosen, cause = pair, significant[0].fit.name
                margins["over_none"] = float(min(pair.gain_ci95[c][0] for c in channels))
                margins["added_over_cause"] = float(min(added[0]["gain_ci95"][c][0] for c in channels))
                reason = (
                    f"its held-out gain with {added[0]['effect']} beside it is significant, every parameter plausible"
                )
    extended = chosen.fit if chosen else baseline
    warnings = (
        beyond_reach(campaign)
        + [dict(f, model="baseline") for f in _findings(baseline)]
        + ([dict(f, model=chosen.fit.name) for f in chosen.findings] if chosen else [])
    )
    discovered: dict[str, dict] = {}
    ratios = {c: heldout_rmse(extended, measured, c) / noise[c] for c in channels if noise[c] > 0}
    remainder = {c: r for c, r in ratios.items() if r > NONE_WITHIN_NOISE}
    if cause == "unexplained" or remainder:
        progress("looking for what the catalog lacks in the residual (sparse regression)")
        discovered = discover_table(campaign, channels, noise, extended, seed)
    where = {c: w for c in remainder if (w := where_left(campaign, extended, measured, c, noise))}
    by_test = {}
    if len(campaign.experiments) > 1:
        progress("predicting each test with the muscle calibrated on the others")
        by_test = heldout_by_test(model, channels, scales, extended, catalog)
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
        discovered,
        remainder,
        by_test,
        where,
    )


def heldout_by_test(model: TableModel, channels, scales, fit: TableFit, catalog: EffectCatalog) -> dict[str, dict]:
    """Each test of a campaign predicted by `fit`'s model (its unknowns and its effects) calibrated
    on the other tests alone: does one characterisation of a muscle carry to another? Per test,
    the held-out RMSE and largest error of each channel its kind predicts, and its noise; a test
    with an unknown of its own (its load), which the others cannot calibrate, says so instead."""
    campaign = model.campaign
    names = [e.name() for e in fit.effects]
    fitter = Fitter(model, channels, scales, [lambda n=n: catalog.make(n) for n in names])
    used = ~campaign.censored
    out = {}
    for index, (experiment, name) in enumerate(zip(campaign.experiments, test_names(campaign.experiments))):
        own = [c.name for c in model.unknowns if c.name == model.unknown_of("load_N", experiment)]
        if own:
            out[name] = {"error": f"{', '.join(own)} is this test's own: the other tests cannot calibrate it"}
            continue
        others = np.flatnonzero(used & (campaign.test != index))
        mine = np.flatnonzero(used & (campaign.test == index))
        if mine.size == 0:
            out[name] = {"error": "every row of this test is censored: nothing of it is scored"}
            continue
        x = fitter.fit(others, [fit.x])
        predicted = fitter.predict(x, mine)
        kind_noise = noise_of(campaign_of([experiment]), tuple(c for c in channels if campaign.predicts(c)[mine[0]]))
        errors = {}
        for c, noise in kind_noise.items():
            residual = predicted[c] - campaign.columns[c][mine]
            errors[c] = {
                "heldout_rmse": float(np.sqrt(np.mean(residual**2))),
                "heldout_max_error": float(np.max(np.abs(residual))),
                "noise": noise,
            }
        out[name] = errors
    return out


def _second_effect(first, candidates, baseline, model, catalog, progress, pool, seed, noise):
    """A second effect beside the best significant candidate `first`: each other candidate is
    fitted jointly with it (from its fit), and the best pair is kept when it gains significantly
    on held-out groups over `first` alone and over the baseline, with every parameter credible.
    A real rig has more than one thing wrong (a hysteresis and a transducer's offset): one name
    cannot hold both, and `first` alone may fit only with a parameter at a bound. Returns the
    pair judged against the baseline and what was added, with its gain over `first` alone; or
    `first` and nothing."""
    campaign, channels = model.campaign, model.channels
    measured = {c: campaign.columns[c] for c in channels}
    used = ~campaign.censored
    scales = {c: float(np.std(measured[c][used & campaign.predicts(c)])) or 1.0 for c in channels}
    best = None
    for other in candidates:
        if other is first:
            continue
        names = [first.fit.name, other.fit.name]
        makes = [lambda n=n: catalog.make(n) for n in names]
        fitter = Fitter(model, channels, scales, makes)
        start = np.concatenate([first.fit.x, [c.start for c in fitter.effect_spaces[1]]])
        progress(f"fitting {names[1]} beside {names[0]}")
        pair = fit_table(
            " + ".join(names), model, channels, scales, makes, campaign.groups, used, pool, [start], noise=noise
        )
        over_cause = _judge(
            pair, first.fit, measured, channels, campaign.groups, used, seed, campaign, acting=pair.effects[1:]
        )
        if over_cause.significant and over_cause.credible and (best is None or over_cause.score > best.score):
            best = over_cause
    if best is None:
        return first, []
    pair = _judge(best.fit, baseline, measured, channels, campaign.groups, used, seed, campaign, _findings(baseline))
    if not (pair.significant and pair.credible):
        return first, []
    effect = best.fit.effects[1].name()
    gains = {"gain": best.gain, "gain_ci95": {c: list(v) for c, v in best.gain_ci95.items()}, "between": best.between}
    return pair, [{"effect": effect, **gains}]


def _decide(candidates, baseline, measured, channels, noise):
    significant = [j for j in candidates if j.significant]
    margins: dict[str, float] = {}
    if significant:
        best = significant[0]
        lead = next((j for j in significant if j.credible), None)
        if not best.credible:
            what = "; ".join(
                f"{f['parameter']} = {f['value']:.4g}"
                + (f" at its search bound {f['bound']:.4g}" if f["bound"] else "")
                for f in best.findings
            )
            rejected = f"{best.fit.name} fits only with {what}"
            if lead is None:
                return "unexplained", f"the best candidate, {rejected}", None, margins
            # The series' rule 3: a better fit that cannot be named stands beside the cause, not in
            # its place, unless it explains the held-out groups better on the same draws, and by
            # MIN_GAIN of what the credible one leaves (what that one fits is then likely a piece of it).
            low = float(np.percentile(best.samples - lead.samples, 2.5))
            ahead = (best.score - lead.score) / (1.0 - lead.score) if lead.score < 1.0 else 0.0
            if low > 0.0 and ahead >= MIN_GAIN:
                return (
                    "unexplained",
                    f"the best candidate, {rejected}; {lead.fit.name} explains significantly less (gain "
                    f"{lead.score:.3f} against {best.score:.3f}) and may be a part of it",
                    None,
                    margins,
                )
            margins["under_rejected"] = max(-low, MIN_GAIN - ahead)
        # The series' rule 6: the cause must beat every other credible one on the same draws;
        # otherwise the two explain the held-out units alike (at a single held length a friction
        # that took up the slack and a transducer's offset are the same line) and naming either
        # is a guess.
        for rival in (j for j in significant if j is not lead and j.credible):
            low, high = np.percentile(lead.samples - rival.samples, [2.5, 97.5])
            margins["over_rival"] = min(margins.get("over_rival", math.inf), float(low))
            if low <= 0.0:
                return (
                    "unexplained",
                    f"{lead.fit.name} and {rival.fit.name} explain the held-out units alike (gain {lead.score:.3f} "
                    f"against {rival.score:.3f}; the difference's 95 % interval [{low:.3g}, {high:.3g}] holds zero): "
                    "the data do not tell the two apart",
                    None,
                    margins,
                )
        runner = next((j for j in candidates if j is not lead), None)
        margins["over_none"] = float(min(lead.gain_ci95[c][0] for c in channels))
        if runner is not None:
            margins["over_runner_up"] = float(lead.score - runner.score)
        reason = "its held-out gain is significant and its parameters plausible"
        if lead is not best:
            reason += f"; {rejected}, no better on the same draws"
        return lead.fit.name, reason, lead, margins
    ratios = {c: heldout_rmse(baseline, measured, c) / noise[c] for c in channels if noise[c] > 0}
    if ratios and max(ratios.values()) <= NONE_WITHIN_NOISE:
        margins["within_noise"] = float(NONE_WITHIN_NOISE - max(ratios.values()))
        return "none", "the calibrated model carries to held-out groups within the noise", None, margins
    left = ", ".join(f"{c} at {r:.1f}x its noise" for c, r in ratios.items())
    return "unexplained", f"no catalog effect gains significantly; held-out error left: {left}", None, margins
