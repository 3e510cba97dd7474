"""Diagnosis of static tables: isometric maps, isotonic tests of settled steps and
free-inflation tables, the kinds docs/experiments.md describes, and beside them a supplied time
series of the same muscle (a cyclic test); their units and noise are in kinds.py, their fits in
fit.py, the candidates' scores and the verdict in decide.py, the search of what is left in
discover.py and where it lies in remainder.py, their report in report.py (all in this package).

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
from dataclasses import dataclass, field

import numpy as np

from pamkit._core import EffectCatalog, EffectStage, GasMode
from pamkit.diagnosis.significance import NONE_WITHIN_NOISE
from pamkit.diagnosis.tables.decide import TableCandidate, decide, findings_of, judge
from pamkit.diagnosis.tables.discover import discover_table
from pamkit.diagnosis.tables.fit import Fitter, TableFit, TableModel, fit_table, heldout_rmse
from pamkit.diagnosis.tables.kinds import MIN_GROUPS, Campaign, beyond_reach, campaign_of, noise_of
from pamkit.diagnosis.tables.remainder import where_left
from pamkit.effects import catalog as builtin_catalog
from pamkit.io.experiment import Experiment, test_names
from pamkit.io.guards import ExperimentError


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


def _seed(columns: dict[str, np.ndarray]) -> int:
    """The bootstrap's seed, drawn from the data: the same tables give the same report."""
    digest = hashlib.sha256()
    for name in sorted(columns):
        digest.update(np.ascontiguousarray(columns[name], dtype="<f8").tobytes())
    return int.from_bytes(digest.digest()[:8], "little")


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
        what = {
            "isometric_map": "measure the map at more held lengths, or pressurise and vent it again",
            "isotonic": "sweep the pressure again, or in more steps",
        }.get(campaign.kind, "add rows")
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
                judge(
                    fit, baseline, measured, channels, groups, used, seed, campaign, findings_of(baseline), noise=noise
                )
            )
        candidates.sort(key=lambda j: -j.score)
        cause, reason, chosen, margins = decide(candidates, baseline, measured, channels, noise)
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
        [{"reading": sentence} for e in campaign.experiments for sentence in e.data_warnings]
        + beyond_reach(campaign)
        + [dict(f, model="baseline") for f in findings_of(baseline)]
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


def _placed_off_neutral(fit, name: str, neutral: float) -> bool:
    """Whether the data determine a fitted value and its 95 % interval excludes its neutral value
    (EffectParameter.neutral; NaN: none, so any determined value is placed)."""
    if name in fit.undetermined:
        return False
    low, high = fit.intervals.get(name, (-math.inf, math.inf))
    return not (math.isfinite(neutral) and low <= neutral <= high)


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
        over_cause = judge(
            pair,
            first.fit,
            measured,
            channels,
            campaign.groups,
            used,
            seed,
            campaign,
            acting=pair.effects[1:],
            noise=noise,
        )
        # An added effect none of whose own values the data determine, or place off the value at
        # which it adds nothing, explains nothing of its own: what its pair gains then comes from
        # where the folds' refits stopped, not from it (a transducer's offset beside a one-sweep
        # isotonic test's friction: gain 0.04 over it, the offset -23 to +1.8 kPa).
        neutral = {p.name: p.neutral for p in makes[1]().parameters()}
        told = any(_placed_off_neutral(pair, f"{names[1]}.{c.name}", neutral[c.name]) for c in fitter.effect_spaces[1])
        if over_cause.significant and over_cause.credible and told and (best is None or over_cause.score > best.score):
            best = over_cause
    if best is None:
        return first, []
    pair = judge(best.fit, baseline, measured, channels, campaign.groups, used, seed, campaign, findings_of(baseline))
    if not (pair.significant and pair.credible):
        return first, []
    effect = best.fit.effects[1].name()
    gains = {"gain": best.gain, "gain_ci95": {c: list(v) for c, v in best.gain_ci95.items()}, "between": best.between}
    return pair, [{"effect": effect, **gains}]
