"""Decisions on a static table (the rules of series/decide.py, on its held-out groups): each
candidate scored against the calibrated baseline over the groups with a bootstrap interval (an
effect that shows only between the branches on what differs between them), its parameters'
findings beside what a supply can do (supply.py), and the verdict: the best credible candidate,
beside a better fit that cannot be named and against a credible rival it must beat on the same
draws (rules 3 and 6), `none` within the noise, else `unexplained`."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

from pamkit._core import EffectStage
from pamkit.diagnosis.coordinates import findings
from pamkit.diagnosis.significance import BOOTSTRAP_SAMPLES, MIN_GAIN, NONE_WITHIN_NOISE
from pamkit.diagnosis.supply import VACUUM_TOLERANCE_PA, implied_vacuum
from pamkit.diagnosis.tables.fit import TableFit, heldout_rmse
from pamkit.diagnosis.tables.kinds import MIN_GROUPS, Campaign
from pamkit.io.columns import value_from_si


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


def findings_of(fit: TableFit) -> list[dict]:
    """coordinates.py's findings (parameters at a search bound or implausible), as report rows."""
    return [asdict(f) for f in findings(fit)]


# The report row of an instrument's error that the model without it does not need (not_needed).
NOT_NEEDED = "heldout_rmse_over_noise_before"


def findings_text(rows: list[dict]) -> str:
    """Report rows of findings as the verdict says them, after "fits only with": "gain = 0.7844 at
    its search bound …"; an instrument's error not needed, as "the model without it …"."""
    return "; ".join(
        f["source"]
        if f["parameter"] == NOT_NEEDED
        else f"{f['parameter']} = {f['value']:.4g}" + (f" at its search bound {f['bound']:.4g}" if f["bound"] else "")
        for f in rows
    )


def vacuum_findings(fit: TableFit, campaign: Campaign) -> list[dict]:
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


def not_needed(before: TableFit, measured, channels, noise: dict[str, float]) -> list[dict]:
    """A report row against an instrument's error where `before` (the model without it) already
    carries to held-out groups within NONE_WITHIN_NOISE of the noise on every channel."""
    ratios = {c: heldout_rmse(before, measured, c) / noise[c] for c in channels if noise[c] > 0}
    if not ratios or max(ratios.values()) > NONE_WITHIN_NOISE:
        return []
    worst = max(ratios.values())
    return [
        {
            "parameter": NOT_NEEDED,
            "value": worst,
            "bound": None,
            "plausible": [NONE_WITHIN_NOISE, None],
            "source": (
                f"the model without it carrying held-out groups within the noise ({worst:.2f}x, "
                f"{NONE_WITHIN_NOISE:g}x allowed): no error of the instrument is needed there"
            ),
            "beyond": None,
            "rmse_drop": None,
        }
    ]


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


def squares(residual: np.ndarray) -> float:
    """A group's sum of squared residuals; NaN (a row of a kind that does not predict the channel)
    adds nothing."""
    return float(np.nansum(residual**2))


def gains(base: np.ndarray, ext: np.ndarray, draws: np.ndarray) -> tuple[float, tuple[float, float], np.ndarray]:
    """Held-out gain from per-group sums of squares, its bootstrap interval over groups and the
    gain on each draw."""
    gain = 1.0 - math.sqrt(ext.sum() / base.sum()) if base.sum() > 0 else 0.0
    samples = 1.0 - np.sqrt(ext[draws].sum(axis=1) / np.maximum(base[draws].sum(axis=1), 1e-300))
    return gain, (float(np.quantile(samples, 0.025)), float(np.quantile(samples, 0.975))), samples


def judge(
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
    noise: dict[str, float] | None = None,
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
    with fewer, every group is judged, as a table of so few groups would be. An instrument's error
    (`acting` all instruments) is not needed where the model it is judged against already carries
    to held-out groups within NONE_WITHIN_NOISE of the `noise` on every channel (the time series'
    rule 6): there it would fit what the build leaves, a finding against it."""
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
        base = np.array([squares(baseline.heldout[c][rows] - measured[c][rows]) for rows in index])
        ext = np.array([squares(fit.heldout[c][rows] - measured[c][rows]) for rows in index])
        gain[c], ci[c], samples[c] = gains(base, ext, draws)
    between = campaign is not None and any(e.shows_between_branches() for e in (acting or fit.effects))
    judged_gain, judged_ci = gain, ci
    if between:
        pressure, branch = campaign.columns["gauge_pressure_Pa"], campaign.branch
        judged_gain, judged_ci, samples = {}, {}, {}
        for c in channels:
            r_base, r_fit = baseline.heldout[c] - measured[c], fit.heldout[c] - measured[c]
            base = np.array([squares(branch_difference(r_base, pressure, branch, rows)) for rows in index])
            ext = np.array([squares(branch_difference(r_fit, pressure, branch, rows)) for rows in index])
            judged_gain[c], judged_ci[c], samples[c] = gains(base, ext, draws)
    score = float(np.mean([judged_gain[c] for c in channels]))
    significant = all(judged_gain[c] >= MIN_GAIN and judged_ci[c][0] > 0.0 for c in channels)
    own, strain = [], []
    corrector = all(e.stage() != EffectStage.physics for e in fit.effects)
    instrument = all(e.stage() != EffectStage.physics for e in (acting or fit.effects))
    unneeded = not_needed(baseline, measured, channels, noise) if instrument and noise is not None else []
    for finding in findings_of(fit) + (vacuum_findings(fit, campaign) if campaign is not None else []) + unneeded:
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


def decide(candidates, baseline, measured, channels, noise):
    """The verdict on `candidates` (judged, best score first): the cause, why, the candidate named
    (or None) and each deciding rule's margin. The best significant, credible candidate is named,
    unless a better fit that cannot be named outdoes it (rule 3) or a credible rival explains the
    held-out groups as well (rule 6); with none significant, or only fits that cannot be named,
    `none` within NONE_WITHIN_NOISE of the noise, else `unexplained`."""
    significant = [j for j in candidates if j.significant]
    margins: dict[str, float] = {}

    def noise_ratios() -> dict[str, float]:
        return {c: heldout_rmse(baseline, measured, c) / noise[c] for c in channels if noise[c] > 0}

    if significant:
        best = significant[0]
        lead = next((j for j in significant if j.credible), None)
        if not best.credible:
            rejected = f"{best.fit.name} fits only with {findings_text(best.findings)}"
            if lead is None:
                # The series' rule 4: with nothing named, the baseline that already reaches the
                # noise is the answer; the rejected fit fitted what the noise allows.
                ratios = noise_ratios()
                if ratios and max(ratios.values()) <= NONE_WITHIN_NOISE:
                    margins["within_noise"] = float(NONE_WITHIN_NOISE - max(ratios.values()))
                    return (
                        "none",
                        f"the calibrated model carries to held-out groups within the noise; the best candidate, "
                        f"{rejected}",
                        None,
                        margins,
                    )
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
    ratios = noise_ratios()
    if ratios and max(ratios.values()) <= NONE_WITHIN_NOISE:
        margins["within_noise"] = float(NONE_WITHIN_NOISE - max(ratios.values()))
        return "none", "the calibrated model carries to held-out groups within the noise", None, margins
    left = ", ".join(f"{c} at {r:.1f}x its noise" for c, r in ratios.items())
    return "unexplained", f"no catalog effect gains significantly; held-out error left: {left}", None, margins
