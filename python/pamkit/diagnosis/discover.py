"""Discovery of what the catalog lacks: sparse regression of a channel's residual on a library of
physically meaningful terms, chosen by held-out error.

When no catalog effect explains the residual (``cause`` is ``"unexplained"``), the residual
``measured - predicted`` of a channel is fitted as a sum of a few terms from a library built
from the record itself — Coulomb friction ``p · tanh(v / v0)``, Dahl friction, viscous ``v``,
stiffness errors ``x, x², x³``, pressure, its rate and the pressurise/vent branch, the load
cell's gain and nonlinearity (F, F²), drifts in time and cycle, the gas temperature above
ambient — and reported as an equation with units, with its held-out
gain and the mechanism each term resembles::

    features = feature_library(time_s, elongation_m, gauge_pressure_Pa)
    result = discover(features, residual, sigma, fit_mask, held_mask, half_cycle, "force_N", "N")
    print(result["equation"])   # force_N residual ≈ 0.0003 N/Pa · p · tanh(v / 2.1 mm/s)
    save_effect(result, "friction.json")  # discovered.py: a pamkit.Effect for the next run

Method (docs/diagnosis.md, rule 10): orthogonal matching pursuit (`pursuit`, checked against
scikit-learn's ``orthogonal_mp``) on columns centred and scaled over the fitted samples, the offset as the
intercept; unshrunk coefficients read as physical constants; the number of terms chosen on
held-out units only, by the one-standard-error rule (Hastie, Tibshirani & Friedman, The
Elements of Statistical Learning, 2nd ed., sec. 7.10), beating no term by ``MIN_Z`` standard
errors (paired over held-out units) and by a tenth of the noise.
"""

from __future__ import annotations

import math

import numpy as np

from pamkit.diagnosis.features import DiscoveryError, Term, _as_column, feature_library

__all__ = ["DiscoveryError", "Term", "discover", "feature_library"]

MAX_TERMS = 5  # an explanation with more terms is not one a reader can check
MIN_Z = 2.0  # the chosen terms must beat "no term" by 2 standard errors (one-sided ~2 %) ...
MIN_RMSE_DROP = 0.1  # ... and lower the held-out RMSE by a tenth of the noise to be worth reading
BOOTSTRAP_SAMPLES = 1000  # as the diagnosis's own gain intervals (engine.BOOTSTRAP_SAMPLES)

# --------------------------------------------------------------------------- the regression


def _per(channel_unit: str, term_unit: str) -> str:
    """Unit of a coefficient: channel unit per term unit."""
    if term_unit == "1":
        return channel_unit
    if term_unit == channel_unit:
        return "1"  # a gain error: the pressure channel against p
    if term_unit == f"{channel_unit}²":
        return f"1/{channel_unit}"  # the force channel against F²
    return f"{channel_unit}/({term_unit})" if "/" in term_unit else f"{channel_unit}/{term_unit}"


def _equation(channel: str, terms: list[dict]) -> str:
    if not terms:
        return f"{channel} residual ≈ 0 (no term beats zero on held-out data)"
    parts = []
    for k, term in enumerate(terms):
        coefficient = term["coefficient"]
        sign = ("- " if coefficient < 0 else "+ ") if k else ("-" if coefficient < 0 else "")
        factor = "" if term["name"] == "offset" else f" · {term['expression']}"
        unit = "" if term["unit"] == "1" else f" {term['unit']}"
        parts.append(f"{sign}{abs(coefficient):.3g}{unit}{factor}")
    return f"{channel} residual ≈ " + " ".join(parts)


def _check_mask(name: str, mask, n: int) -> np.ndarray:
    array = np.asarray(mask)
    if array.dtype != bool or array.shape != (n,):
        raise DiscoveryError(f"{name} must be a boolean array of {n} samples, got {array.dtype} of shape {array.shape}")
    return array


def _least_squares(design: np.ndarray, target: np.ndarray) -> np.ndarray:
    return np.linalg.lstsq(design, target, rcond=None)[0]


def pursuit(columns: np.ndarray, target: np.ndarray, max_terms: int) -> list[list[int]]:
    """Orthogonal matching pursuit (Pati, Rezaiifar and Krishnaprasad, 1993) on unit-norm
    `columns`: the columns chosen after each step, in ascending order, at most `max_terms` steps.
    Each step takes the column most correlated with what the chosen ones leave of `target` and
    refits all chosen by least squares. The path ends early where that column is one already
    chosen, one the chosen columns span, or one uncorrelated with the target, as scikit-learn's
    ``orthogonal_mp`` ends it. Written here rather than imported: importing scikit-learn costs
    about 1.6 s, two thirds of a diagnosis that ends with a remainder, for these few lines; the
    tests check the path against ``sklearn.linear_model.orthogonal_mp``."""
    tiny = np.finfo(float).eps
    correlation_with_target = columns.T @ target
    chosen: list[int] = []
    residual = target
    path = []
    for _ in range(max_terms):
        best = int(np.argmax(np.abs(columns.T @ residual)))
        if best in chosen or correlation_with_target[best] ** 2 < tiny:
            break
        if chosen:
            basis = columns[:, chosen]
            spanned = basis @ np.linalg.lstsq(basis, columns[:, best], rcond=None)[0]
            if np.sum((columns[:, best] - spanned) ** 2) <= tiny:
                break
        chosen.append(best)
        residual = target - columns[:, chosen] @ _least_squares(columns[:, chosen], target)
        path.append(sorted(chosen))
    return path


def _candidate_models(terms: list[Term], X_fit: np.ndarray, residual_fit: np.ndarray) -> list[list[int]]:
    """Nested models, fewest terms first: none; the offset alone; then the offset with the
    first 1, 2, ... MAX_TERMS terms that orthogonal matching pursuit picks from the other
    columns centred on the fitted samples. Centring leaves the offset to the intercept: with raw
    columns every term of positive mean (pressure, x²) would stand in for an offset before the
    offset itself is picked. Without an offset column: none, then the pursuit on raw columns."""
    offset = next((j for j, t in enumerate(terms) if t.name == "offset"), None)
    others = np.array([j for j in range(len(terms)) if j != offset])
    columns = X_fit[:, others]
    target = residual_fit
    if offset is not None:
        columns = columns - columns.mean(axis=0)
        target = residual_fit - residual_fit.mean()
    # The pursuit takes unit-norm columns; a column constant on the fitted samples cannot be picked.
    norms = np.linalg.norm(columns, axis=0)
    usable = norms > 1e-12 * max(float(norms.max(initial=0.0)), 1e-300)
    candidates = others[usable]
    models: list[list[int]] = [[]] + ([[offset]] if offset is not None else [])
    for step in pursuit(columns[:, usable] / norms[usable], target, min(MAX_TERMS, int(candidates.size))):
        models.append(candidates[step].tolist() + ([offset] if offset is not None else []))
    return models


def discover(
    features: dict[Term, np.ndarray],
    residual: np.ndarray,
    noise_sigma: float,
    fit_mask: np.ndarray,
    held_mask: np.ndarray,
    held_units: np.ndarray,
    channel: str,
    channel_unit: str,
    seed: int = 0,
) -> dict:
    """Sparse regression of one channel's residual on the feature library.

    Args:
        features: feature_library's output (on all samples).
        residual: measured - predicted of the channel [channel_unit], on all samples.
        noise_sigma: the channel's white-noise standard deviation [channel_unit]; gives each
            coefficient's standard error and the gain a perfect explanation would reach.
        fit_mask, held_mask: samples to fit on and samples to judge on (disjoint).
        held_units: unit id of every sample (half-cycle, sweep); held-out errors are compared
            and bootstrapped over the units in held_mask.
        channel, channel_unit: e.g. "force_N", "N".
        seed: of the bootstrap.

    Returns:
        A JSON-ready dict: channel; terms, each with expression, coefficient, unit (of the
        coefficient), resembles, standard_error, name, parameters; gain and gain_ci95 per
        channel (held-out, 1 - rmse(residual - fit) / rmse(residual)); gain_attainable (1 -
        noise_sigma / rmse(residual), the gain of a perfect explanation); heldout_rmse_path,
        the held-out RMSE of the candidates (no term, the offset, then the offset with 1, 2, ...
        terms); equation. No term that beats zero on held-out data: terms [], gain 0.

    Raises:
        DiscoveryError: naming the argument of the wrong size or type, or too few held-out units.
    """
    residual = _as_column("residual", residual, None)
    n = residual.size
    fit_mask = _check_mask("fit_mask", fit_mask, n)
    held_mask = _check_mask("held_mask", held_mask, n)
    if np.any(fit_mask & held_mask):
        raise DiscoveryError(f"fit_mask and held_mask share {int(np.sum(fit_mask & held_mask))} sample(s)")
    held_units = np.asarray(held_units)
    if held_units.shape != (n,):
        raise DiscoveryError(f"held_units has shape {held_units.shape}, residual has {n} samples")
    if not (math.isfinite(noise_sigma) and noise_sigma > 0.0):
        raise DiscoveryError(f"noise_sigma = {noise_sigma} must be a positive number")
    terms = list(features)
    if not terms:
        raise DiscoveryError("features is empty: feature_library found no term to try")
    X = np.column_stack([_as_column(f"feature {t.name}", features[t], n, "residual") for t in terms])
    units, unit_of_sample = np.unique(held_units[held_mask], return_inverse=True)
    if units.size < 2:
        raise DiscoveryError(f"held_mask covers {units.size} unit(s); judging a term needs at least 2 held-out units")
    if int(fit_mask.sum()) <= len(terms):
        raise DiscoveryError(f"fit_mask has {int(fit_mask.sum())} samples for {len(terms)} terms")

    models = _candidate_models(terms, X[fit_mask], residual[fit_mask])
    fits = [_least_squares(X[fit_mask][:, model], residual[fit_mask]) for model in models]
    held_residual = residual[held_mask]
    # Sum of squared held-out errors per candidate and unit.
    unit_sse = np.array(
        [
            np.bincount(unit_of_sample, weights=(held_residual - X[held_mask][:, model] @ c) ** 2, minlength=units.size)
            for model, c in zip(models, fits)
        ]
    )
    total = unit_sse.sum(axis=1)

    def standard_error(a: int, b: int) -> float:
        difference = unit_sse[a] - unit_sse[b]
        return float(math.sqrt(units.size) * np.std(difference, ddof=1))

    rmse = np.sqrt(total / held_residual.size)
    material = MIN_RMSE_DROP * noise_sigma

    def as_good_as_best(k: int) -> bool:
        """Candidate k is within one standard error of the best, or short of it by less than matters."""
        return total[k] - total[best] <= standard_error(k, best) or rmse[k] - rmse[best] <= material

    def beats_nothing(k: int) -> bool:
        return total[0] - total[k] > MIN_Z * standard_error(0, k) and rmse[0] - rmse[k] > material

    best = int(np.argmin(total))
    # The fewest terms that are as good as the best and beat no term at all.
    chosen = next((k for k in range(1, best + 1) if as_good_as_best(k) and beats_nothing(k)), 0)

    attainable = 1.0 - noise_sigma / rmse[0] if rmse[0] > 0 else 0.0
    result = {
        "channel": channel,
        "channel_unit": channel_unit,
        "terms": [],
        "gain": {channel: 0.0},
        "gain_ci95": {channel: [0.0, 0.0]},
        "gain_attainable": {channel: float(attainable)},
        "heldout_rmse_path": [float(value) for value in rmse],
        "equation": _equation(channel, []),
    }
    if chosen == 0:
        return result

    model, coefficients, chosen_sse = models[chosen], fits[chosen], unit_sse[chosen]
    offset = next((j for j, t in enumerate(terms) if t.name == "offset"), None)
    if offset in model and len(model) > 1:
        # The path carries an offset with every model; keep it only if it matters on held-out data.
        without = [j for j in model if j != offset]
        c = _least_squares(X[fit_mask][:, without], residual[fit_mask])
        sse = np.bincount(
            unit_of_sample, weights=(held_residual - X[held_mask][:, without] @ c) ** 2, minlength=units.size
        )
        if math.sqrt(sse.sum() / held_residual.size) - rmse[chosen] <= material:
            model, coefficients, chosen_sse = without, c, sse

    design = X[fit_mask][:, model]
    # White-noise standard errors of the least-squares coefficients.
    covariance = noise_sigma**2 * np.linalg.inv(design.T @ design)
    found = []
    for j, column in enumerate(model):
        term, coefficient = terms[column], float(coefficients[j])
        size = abs(coefficient) * float(np.sqrt(np.mean(X[held_mask, column] ** 2)))
        found.append(
            (
                size,
                {
                    "expression": term.expression,
                    "coefficient": coefficient,
                    "unit": _per(channel_unit, term.unit),
                    "resembles": term.resembles,
                    "standard_error": float(math.sqrt(covariance[j, j])),
                    "name": term.name,
                    "parameters": dict(term.parameters),
                },
            )
        )
    reported = [entry for _, entry in sorted(found, key=lambda pair: -pair[0])]  # largest contribution first

    rng = np.random.default_rng(seed)
    draws = rng.integers(0, units.size, size=(BOOTSTRAP_SAMPLES, units.size))
    boot_fit = chosen_sse[draws].sum(axis=1)
    boot_zero = unit_sse[0][draws].sum(axis=1)
    boot_gain = 1.0 - np.sqrt(boot_fit / np.maximum(boot_zero, 1e-300))
    result.update(
        {
            "terms": reported,
            "gain": {channel: float(1.0 - math.sqrt(chosen_sse.sum() / total[0]))},
            "gain_ci95": {channel: [float(np.percentile(boot_gain, 2.5)), float(np.percentile(boot_gain, 97.5))]},
            "equation": _equation(channel, reported),
        }
    )
    return result
