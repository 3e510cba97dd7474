"""The report of a static table's diagnosis: the JSON keys of docs/reference/report.md (with the calibrated
unknowns' intervals and the held-out error per unit) and the verdict a person reads first (its
figure is figure.py)."""

from __future__ import annotations

import numpy as np

from pamkit.diagnosis.identify import interval_numbers, why_undetermined
from pamkit.diagnosis.tables.decide import TableCandidate, findings_text
from pamkit.diagnosis.tables.engine import TableDiagnosis
from pamkit.diagnosis.tables.fit import HELD_IN_TABLES, TableFit, heldout_rmse
from pamkit.diagnosis.tables.remainder import describe
from pamkit.io.columns import COLUMN_UNITS


def to_json(d: TableDiagnosis) -> dict:
    measured = {c: d.campaign.columns[c] for c in d.channels}
    used = ~d.campaign.censored

    def rmse(fit, heldout):
        if heldout:
            return {c: heldout_rmse(fit, measured, c) for c in d.channels}
        return {c: float(np.sqrt(np.nanmean((fit.predicted[c] - measured[c])[used] ** 2))) for c in d.channels}

    def per_group(fit):
        out = {}
        for index, label in enumerate(d.campaign.group_labels):
            rows = (d.groups == index) & used
            if rows.any():
                errors = {c: heldout_rmse(fit, measured, c, rows) for c in d.channels}
                out[label] = {c: e for c, e in errors.items() if np.isfinite(e)}  # the channels its kind predicts
        return out

    def largest(fit):
        return {c: float(np.nanmax(np.abs(fit.heldout[c] - measured[c])[used])) for c in d.channels}

    report = {
        "kind": d.campaign.kind,
        "verdict": verdict(d),
        "tests": [str(e.path) for e in d.campaign.experiments],
        "held_out": d.campaign.group_name,
        "censored_rows": int((~used).sum()),
        "noise": d.noise,
        "baseline": {
            "params": d.baseline.params,
            "intervals": {k: list(v) for k, v in d.baseline.intervals.items()},
            "undetermined": _undetermined_json(d.baseline),
            "rmse": rmse(d.baseline, False),
            "heldout_rmse": rmse(d.baseline, True),
            "heldout_max_error": largest(d.baseline),
            "heldout_rmse_by_group": per_group(d.baseline),
        },
        "candidates": [
            {
                "effect": j.fit.name,
                "params": j.fit.params,
                "heldout_rmse": rmse(j.fit, True),
                "gain": j.gain,
                "gain_ci95": {c: list(v) for c, v in j.gain_ci95.items()},
                "score": j.score,
                "significant": j.significant,
                "credible": j.credible,
                "findings": j.findings,
                "untested": j.untested,
            }
            for j in d.candidates
        ],
        "skipped": d.skipped,
        "cause": d.cause,
        "reason": d.reason,
        "extended": {
            "effects": [e.name() for e in d.extended.effects],
            "params": d.extended.params,
            "intervals": {k: list(v) for k, v in d.extended.intervals.items()},
            "undetermined": _undetermined_json(d.extended),
            "rmse": rmse(d.extended, False),
            "heldout_rmse": rmse(d.extended, True),
            "heldout_max_error": largest(d.extended),
            "heldout_rmse_by_group": per_group(d.extended),
        },
        "gain": d.extended_candidate.gain if d.extended_candidate else {c: 0.0 for c in d.channels},
        "gain_ci95": ({c: list(v) for c, v in d.extended_candidate.gain_ci95.items()} if d.extended_candidate else {}),
        "added": d.added,
        "causes": causes_json(d),
        "remainder": (
            {"channels": d.remainder, "where": d.remainder_where, "discovered": d.discovered_by_channel}
            if d.remainder
            else None
        ),
        "discovered": d.discovered,
        "discovered_by_channel": d.discovered_by_channel,
        "decision": {"cause": d.cause, "reason": d.reason, "margins": d.margins},
        "warnings": d.warnings,
        "heldout_by_test": d.by_test,
    }
    return report


def _undetermined_json(fit: TableFit) -> dict:
    out = {}
    for name, partners in fit.undetermined.items():
        coordinate, x = fit.coordinates[name]
        out[name] = {"trades_against": partners, "why": why_undetermined(partners, coordinate.at_bound(x) is not None)}
    return out


def _effect_params(fit: TableFit, name: str) -> dict:
    """One effect's fitted parameters (a pair's are prefixed with the effect's name)."""
    if len(fit.effects) < 2:
        names = {p.name for e in fit.effects for p in e.parameters()}
        return {k: v for k, v in fit.params.items() if k in names}
    return {k.split(".", 1)[1]: v for k, v in fit.params.items() if k.startswith(f"{name}.")}


def _held_params(fit: TableFit, name: str) -> dict:
    """One effect's parameters held at their neutral values in a table (HELD_IN_TABLES)."""
    return {
        p.name: p.value
        for e in fit.effects
        if e.name() == name
        for p in e.parameters()
        if p.name in HELD_IN_TABLES.get(name, ())
    }


def causes_json(d: TableDiagnosis) -> list[dict]:
    """Each cause present, the leading one first, with its own held-out gain: the first over the
    calibrated baseline, one added beside it over the first alone; an effect between the
    branches judged on what differs between them (`between`)."""
    if d.extended_candidate is None:
        return []
    lead = next(j for j in d.candidates if j.fit.name == d.cause)
    out = [
        {
            "effect": d.cause,
            "params": _effect_params(d.extended, d.cause),
            "held": _held_params(d.extended, d.cause),
            "gain": lead.gain,
            "gain_ci95": {c: list(v) for c, v in lead.gain_ci95.items()},
            "between_branches": lead.between,
            "over": "baseline",
            "base_model_strain": lead.strain,
        }
    ]
    for more in d.added:
        out.append(
            {
                "effect": more["effect"],
                "params": _effect_params(d.extended, more["effect"]),
                "held": _held_params(d.extended, more["effect"]),
                "gain": more["gain"],
                "gain_ci95": more["gain_ci95"],
                "between_branches": more.get("between"),
                "over": d.cause,
                "base_model_strain": [],
            }
        )
    return out


def _calibrated(fit: TableFit) -> str:
    def one(k, v):
        if k not in fit.undetermined:
            value, low, high = interval_numbers(v, *fit.intervals[k])
            return f"{k} = {value} [{low}, {high}]"
        coordinate, x = fit.coordinates[k]
        why = why_undetermined(fit.undetermined[k], coordinate.at_bound(x) is not None)
        return f"{k} = {v:.4g} (not determined by the data: {why})"

    held = [
        f"{k} = {v:.4g} (held: a table cannot tell it from the build)"
        for e in fit.effects
        for k, v in _held_params(fit, e.name()).items()
    ]
    return ", ".join([one(k, v) for k, v in fit.params.items()] + held)


def _untested(j: TableCandidate, group_name: str) -> str:
    """The groups left out of a candidate's held-out gain, and why, as the verdict adds it."""
    if not j.untested:
        return ""
    parts = "; ".join(f"{group}, predicted with {', '.join(values)}" for group, values in j.untested.items())
    return f" (not tested on {parts}, which the other {group_name}s do not determine)"


def _gains(gain: dict, ci95: dict, channels) -> str:
    """Each channel's held-out gain with its 95 % interval: "force_N 0.92 [0.90, 0.95], ..."."""
    return ", ".join(f"{c} {gain[c]:.2f} [{ci95[c][0]:.2f}, {ci95[c][1]:.2f}]" for c in channels)


def verdict(d: TableDiagnosis) -> str:
    """What a person reads first: the calibrated unknowns with their intervals, the held-out
    error before and after, the cause and its gain, and every parameter at a bound."""
    measured = {c: d.campaign.columns[c] for c in d.channels}
    c = d.campaign
    lines = [f"{c.name}: {c.kind}, {len(c.groups)} rows, each {c.group_name} held out in turn"]
    if c.censored.any():
        lines.append(
            f"{int(c.censored.sum())} row(s) read the pressure transducer's range end: the pressure that drove them "
            "is unknown; predicted, never fitted or scored"
        )
    named = " and ".join([d.cause] + [a["effect"] for a in d.added])
    models = [("baseline", d.baseline)] + ([(f"with {named}", d.extended)] if d.extended is not d.baseline else [])
    used = ~c.censored
    for name, fit in models:
        error = ", ".join(
            f"{ch} {heldout_rmse(fit, measured, ch):.4g} {COLUMN_UNITS[ch]} (noise {d.noise[ch]:.2g}; largest "
            f"{np.nanmax(np.abs(fit.heldout[ch] - measured[ch])[used]):.4g})"
            for ch in d.channels
        )
        lines.append(f"{name}: held-out RMSE {error}")
        if fit.params:
            lines.append(f"  calibrated (jackknife 95 %): {_calibrated(fit)}")
    if d.extended_candidate is None:
        lines.append(f"cause: {d.cause} — {d.reason}")
    else:
        gain = _gains(d.extended_candidate.gain, d.extended_candidate.gain_ci95, d.channels)
        lines.append(f"cause: {d.cause} — held-out gain {gain}{_untested(d.extended_candidate, c.group_name)}")
        for added in d.added:
            more = _gains(added["gain"], added["gain_ci95"], d.channels)
            lines.append(f"also: {added['effect']} — held-out gain over {d.cause} alone {more}")
            if added.get("between"):  # what it was judged on: the branches' difference, where it acts
                between = _gains(added["between"]["gain"], added["between"]["gain_ci95"], d.channels)
                lines.append(f"  between the pressurising and venting branches, where it acts: {between}")
        lead = next(j for j in d.candidates if j.fit.name == d.cause)
        if lead.between:
            between = _gains(lead.between["gain"], lead.between["gain_ci95"], d.channels)
            lines.append(f"  between the pressurising and venting branches, where it acts: held-out gain {between}")
        better = next(j for j in d.candidates if j.significant)
        if better is not lead and not d.added:
            lines.append(f"  {better.fit.name} fits as well, but only with {findings_text(better.findings)}: not named")
        if lead.strain:
            strained = "; ".join(f"{f['parameter']} = {f['value']:.4g}" for f in lead.strain)
            lines.append(f"  beside it the base model strains, as without it: {strained}")
        if d.remainder:
            left = ", ".join(f"{c} at {r:.1f}x its noise" for c, r in d.remainder.items())
            lines.append(f"still left: {left}")
            lines += [f"  {ch}: {describe(w, d.campaign.group_name)}" for ch, w in d.remainder_where.items()]
        else:
            lines.append("nothing is left above the noise")
    if d.by_test:
        lines.append("each test predicted by the muscle calibrated on the others alone:")
        for name, errors in d.by_test.items():
            if "error" in errors:
                lines.append(f"  {name}: {errors['error']}")
                continue
            shown = ", ".join(
                f"{ch} {e['heldout_rmse']:.4g} {COLUMN_UNITS[ch]} (noise {e['noise']:.2g}; largest "
                f"{e['heldout_max_error']:.4g})"
                for ch, e in errors.items()
            )
            lines.append(f"  {name}: {shown}")
    for channel, found in d.discovered_by_channel.items():
        if found.get("terms"):
            low, high = found["gain_ci95"][channel]
            lines.append(
                f"discovered: {found['equation']} (held-out gain {found['gain'][channel]:.2f} "
                f"[{low:.2f}, {high:.2f}]); its largest term resembles {found['terms'][0]['resembles']}"
            )
        elif "error" in found:
            lines.append(f"discovered in {channel}: not searched: {found['error']}")
        else:
            lines.append(f"discovered in {channel}: no term beats zero on held-out {d.campaign.group_name}s")
    for w in d.warnings:
        if "message" in w or "reading" in w:  # the data against the declared test, or as read
            lines.append(f"warning: {w.get('message') or w['reading']}")
            continue
        where = f"at its bound {w['bound']:.4g}" if w["bound"] is not None else "outside its plausible range"
        finding = f"{w['parameter']} = {w['value']:.4g} {where} ({w['source']})"
        if w.get("model") == "baseline" and d.extended is not d.baseline:
            # The baseline's strain, which the model with the cause may not share: said apart.
            finding = f"without {named}, {finding}"
            if w["parameter"] in d.extended.params:
                finding += f"; with it, {w['parameter']} = {d.extended.params[w['parameter']]:.4g}"
        lines.append(f"warning: {finding}")
    return "\n".join(lines)
