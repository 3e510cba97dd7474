"""Where a table's remainder lies: the held-out group holding most of a channel's error, whether
that group lies beyond the lengths the other groups cover (held out, it is then predicted by
extrapolation), and whether its prediction rests on a value only it determines. The report says
it under "still left"."""

from __future__ import annotations

import numpy as np

from pamkit.diagnosis.tables.fit import TableFit
from pamkit.diagnosis.tables.kinds import Campaign


def where_left(campaign: Campaign, fit: TableFit, measured, channel: str, noise: dict[str, float]) -> dict:
    """Where a channel's held-out error lies: the group holding the largest share of its squared
    error, that group's held-out RMSE over the noise and the other groups', and how far the group's
    lengths reach beyond those the other groups of its test cover. Held out, such a group is
    predicted by extrapolation (the longest length of a map, an isotonic test's first sweep from
    rest): its error says as much about what the other groups cannot tell as about the model. A
    length counts as beyond only by more than three times the length's noise where the length is
    measured. `rests_on` names the values the group's held-out prediction depends on that only the
    group determines (fit.rests_on). Empty with fewer than two groups scored."""
    residual = fit.heldout[channel] - measured[channel]
    scored = np.isfinite(residual) & ~campaign.censored
    labels = np.unique(campaign.groups[scored])
    if labels.size < 2:
        return {}
    squared = np.bincount(campaign.groups[scored], weights=residual[scored] ** 2, minlength=len(campaign.group_labels))
    worst = int(np.argmax(squared))
    mine, rest = scored & (campaign.groups == worst), scored & (campaign.groups != worst)

    def ratio(rows):
        return float(np.sqrt(np.mean(residual[rows] ** 2))) / noise[channel]

    out = {
        "group": campaign.group_labels[worst],
        "share": float(squared[worst] / squared.sum()),
        "ratio": ratio(mine),
        "others_ratio": ratio(rest),
        "rows": int(mine.sum()),
        "rows_beyond": 0,
        "beyond_m": 0.0,
        "rests_on": fit.rests_on.get(worst, []),
    }
    lengths = campaign.columns.get("length_m")
    if lengths is None:
        return out
    test = campaign.test[mine][0]
    others = rest & (campaign.test == test) & np.isfinite(lengths)
    if not others.any():
        return out
    here = lengths[mine]
    # A row with no length (a test of a kind that measures none) lies beyond nothing.
    beyond = np.nan_to_num(np.maximum(lengths[others].min() - here, here - lengths[others].max()), nan=0.0).clip(0.0)
    beyond[beyond <= 3.0 * noise.get("length_m", 0.0)] = 0.0
    out["rows_beyond"] = int(np.count_nonzero(beyond))
    out["beyond_m"] = float(beyond.max(initial=0.0))
    return out


def describe(w: dict, group_name: str) -> str:
    """`where_left`'s finding as a sentence; `group_name` names a group ("held length", "sweep")."""
    where = "most of it" if w["share"] >= 0.5 else "the largest share"
    out = (
        f"{where} in {w['group']} ({100 * w['share']:.0f} % of the squared error; {w['ratio']:.1f}x its noise there, "
        f"{w['others_ratio']:.1f}x over the other {group_name}s)"
    )
    if w["rows_beyond"]:
        out += (
            f", up to {w['beyond_m']:.3g} m beyond the lengths of the other {group_name}s ({w['rows_beyond']} of its "
            f"{w['rows']} rows): held out, it is predicted by extrapolation"
        )
    if w.get("rests_on"):
        out += (
            f"; held out, it is predicted with {', '.join(w['rests_on'])}, which the other {group_name}s do not "
            f"determine"
        )
    return out
