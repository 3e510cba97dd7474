"""Discovery on static tables: what a table's calibrated model leaves, as a few physical terms.

A table has no time axis, so the library is built from what a settled row has: its supplied
pressure, its pressurise/vent branch, its held length (a map) and the channel's own predicted
value. The regression, the choice of terms on held-out groups and the gain with its interval
are the shared discovery's (pamkit.diagnosis.discover), unchanged; here the groups alternate
between fitting and judging (the first, third, ... group fitted; the others held out), and
censored rows take part in neither.
"""

from __future__ import annotations

import numpy as np

from pamkit.diagnosis.discover import discover
from pamkit.diagnosis.features import DiscoveryError, Term
from pamkit.diagnosis.significance import NONE_WITHIN_NOISE
from pamkit.io.columns import value_from_si
from pamkit.io.experiment import test_names

UNITS = {"force_N": "N", "length_m": "m", "diameter_m": "m"}
# A channel is searched when its held-out RMSE exceeds the factor within which a model is said
# to explain a table (significance.py).
NOISE_FACTOR = NONE_WITHIN_NOISE


def table_features(
    kind: str,
    columns: dict[str, np.ndarray],
    tests: np.ndarray,
    branch: np.ndarray,
    channel: str,
    predicted: np.ndarray,
    names=(),
):
    """The terms a row of this kind of table can be explained by, each with its column; in a
    campaign, one indicator per test after the first (`names` its tests' names); the
    pressurise/vent `branch` of each row (+1/-1)."""
    # In kPa: p² in Pa² (~1e11) would stand eleven decades beside the offset in one least-squares solve.
    pressure = value_from_si("gauge_pressure_Pa", columns["gauge_pressure_Pa"])
    unit = UNITS[channel]
    features = {
        Term("offset", "1", "1", "a constant error: the instrument's zero, or a fixed length of the fittings"): (
            np.ones_like(pressure)
        )
    }
    for index, name in list(enumerate(names))[1:]:
        features[Term(f"test:{name}", f"[{name}]", "1", f"{name}'s build differs from the shared one")] = (
            tests == index
        ).astype(float)
    features[Term("p", "p", "kPa", "an error growing with pressure: the membrane's stiffness, a transducer's gain")] = (
        pressure
    )
    features[Term("y", channel, unit, "a scale error of the channel: the instrument's gain, a dimension off")] = (
        predicted
    )
    features[Term("p^2", "p²", "kPa²", "an error growing faster than pressure: the membrane stiffening")] = pressure**2
    if np.any(branch < 0):  # both branches: their difference is a term
        features[Term("branch", "b (+1 pressurising, -1 venting)", "1", "rate-independent friction")] = branch
        features[Term("p*branch", "p · b", "kPa", "friction between bladder and braid, growing with pressure")] = (
            pressure * branch
        )
    if kind == "isometric_map":
        stretch = columns["length_m"] - float(np.mean(columns["length_m"]))
        features[Term("p*dL", "p · (L - L̄)", "kPa·m", "a braid angle or end length off: force per pressure")] = (
            pressure * stretch
        )
    return features


def discover_table(campaign, channels, noise: dict[str, float], fit, seed: int) -> dict[str, dict]:
    """Sparse regression of what `fit` (a TableFit) leaves in each channel beyond NOISE_FACTOR
    times its noise, the furthest first: pamkit.diagnosis.discover's result per channel, or its error."""
    measured = {c: campaign.columns[c] for c in channels}
    used = ~campaign.censored

    def above_noise(c):
        return float(np.sqrt(np.nanmean((fit.heldout[c] - measured[c])[used] ** 2))) / noise[c]

    ranked = sorted((c for c in channels if above_noise(c) > NOISE_FACTOR), key=above_noise, reverse=True)
    return {
        c: _discover_channel(
            campaign, c, noise[c], np.nan_to_num(measured[c] - fit.predicted[c]), fit.predicted[c], seed
        )
        for c in ranked
    }


def _discover_channel(campaign, channel: str, noise: float, residual, predicted, seed: int) -> dict:
    used = ~campaign.censored & campaign.predicts(channel)  # a campaign's other kinds do not predict it
    labels = np.unique(campaign.groups[used])
    fitted_labels = labels[::2]
    if labels.size - fitted_labels.size < 2:
        return {
            "channel": channel,
            "terms": [],
            "error": (
                f"{labels.size} {campaign.group_name}s: a term is fitted on every other one and judged on the rest, "
                "which takes at least 4"
            ),
        }
    fit_mask = used & np.isin(campaign.groups, fitted_labels)
    held_mask = used & ~np.isin(campaign.groups, fitted_labels)
    names = test_names(campaign.experiments) if len(campaign.experiments) > 1 else ()
    try:
        features = table_features(
            campaign.kind, campaign.columns, campaign.test, campaign.branch, channel, np.nan_to_num(predicted), names
        )
        # A table of a few rows affords fewer terms than rows fitted: the first ones, in the
        # library's order (simplest first).
        features = dict(list(features.items())[: max(int(fit_mask.sum()) - 1, 1)])
        return discover(
            features,
            residual,
            noise,
            fit_mask,
            held_mask,
            campaign.groups,
            channel,
            UNITS[channel],
            seed=seed % 2**32,
        )
    except DiscoveryError as error:
        return {"channel": channel, "terms": [], "error": str(error)}
