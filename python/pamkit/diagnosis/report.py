"""The diagnosis as JSON (the keys of docs/reference/report.md), as a sentence, and as a figure;
the muscle it found, as a parameters file: params_out.py."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from pamkit.diagnosis import evidence
from pamkit.diagnosis.figure import plot_series, series_figure
from pamkit.diagnosis.identify import interval_numbers, why_undetermined
from pamkit.diagnosis.series import campaign
from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.campaign import SeriesCampaign
from pamkit.diagnosis.series.decide import Judgement, gain_over
from pamkit.diagnosis.series.instruments import noise_ratios
from pamkit.diagnosis.series.remainder import describe, where_left
from pamkit.diagnosis.series.result import Diagnosis
from pamkit.diagnosis.series.score import credited_channels
from pamkit.diagnosis.series.separate import SEPARATES
from pamkit.diagnosis.significance import MIN_BIC_DROP, MIN_GAIN, NONE_WITHIN_NOISE
from pamkit.diagnosis.tables import figure as table_figure
from pamkit.diagnosis.tables import report as table_report
from pamkit.diagnosis.tables.engine import TableDiagnosis
from pamkit.io.columns import COLUMN_UNITS, difference_from_si, file_name, file_unit


def _heldout_rmse(d: Diagnosis, fit: Fit) -> dict[str, float]:
    p = d.problem
    return {c: evidence.rmse((fit.predicted[c] - p.measured[c])[p.held_mask]) for c in p.channels}


def _residual_evidence(d: Diagnosis, fit: Fit) -> dict:
    p = d.problem
    time = p.experiment.time_s
    elongation = p.experiment.elongation_m
    velocity = np.gradient(elongation, time)
    regressors = {
        "elongation": elongation,
        "velocity": velocity,
        "abs_velocity": np.abs(velocity),
        "time": time,
        "cycle": p.cycle.astype(float),
    }
    mask = p.held_mask
    out = {"ljung_box_p": {}, "correlation": {}, "best_lag_s": {}}
    for c in p.channels:
        r = (fit.predicted[c] - p.measured[c])[mask]
        out["ljung_box_p"][c] = evidence.ljung_box_p(r)
        out["correlation"][c] = evidence.correlations(r, {k: v[mask] for k, v in regressors.items()})
        rate = np.gradient(fit.predicted[c], time)[mask]
        out["best_lag_s"][c] = evidence.lagged_correlation_peak(r, rate, time[mask])
    return out


def to_json(d: Diagnosis | TableDiagnosis | SeriesCampaign) -> dict:
    """The report as JSON, with the keys docs/reference/report.md defines."""
    if isinstance(d, TableDiagnosis):
        return table_report.to_json(d)
    if isinstance(d, SeriesCampaign):
        return campaign.to_json(d, to_json)
    p = d.problem
    baseline_rmse = _heldout_rmse(d, d.baseline)
    named = d.extended_judgement
    report = {
        "baseline": {
            "params": d.baseline.params,
            "intervals": {k: list(v) for k, v in d.baseline.intervals.items()},
            "undetermined": undetermined_json(d.baseline),
            "rmse": baseline_rmse,
        },
        "candidates": [
            {
                "effect": j.fit.name,
                "params": j.fit.params,
                "heldout_rmse": j.score.rmse,
                "gain": j.score.gain,
                "gain_ci95": j.score.gain_ci95,
                "score": j.score.combined_gain,
                "score_ci95": j.score.combined_ci95,
                "delta_bic": j.score.delta_bic,
                "significant": j.significant,
                "credible": j.credible,
                "not_credible_because": j.reasons(),
                # not fitted beyond one Gauss-Newton step: the fitted chi-square's drop it predicted
                "screened_drop": j.fit.screened,
            }
            for j in d.candidates
        ],
        "cause": d.cause,
        "extended": {
            "effects": [e.name() for e in d.extended.effects],
            "params": {**d.extended.baseline_params, **d.extended.params},
            "intervals": {k: list(v) for k, v in d.extended.intervals.items()},
            "undetermined": undetermined_json(d.extended),
            "rmse": _heldout_rmse(d, d.extended),
        },
        "gain": named.score.gain if named else {c: 0.0 for c in p.channels},
        "gain_ci95": named.score.gain_ci95 if named else {c: [0.0, 0.0] for c in p.channels},
        "residuals": {"baseline": _residual_evidence(d, d.baseline), "extended": _residual_evidence(d, d.extended)},
        "evidence": {
            "noise": p.sigma,
            "peak_difference": {
                c: evidence.peak_difference(
                    p.measured[c][p.held_mask], d.baseline.predicted[c][p.held_mask], p.cycle[p.held_mask]
                )
                for c in p.channels
            },
            "units": p.unit_name,
            "cycles": {
                "fitted": sorted(set(int(k) for k in p.cycle[p.fit_mask])),
                "held_out": sorted(set(int(k) for k in p.cycle[p.held_mask])),
            },
            "min_gain": MIN_GAIN,
            "min_bic_drop": MIN_BIC_DROP,
            "none_within_noise": NONE_WITHIN_NOISE,
            "skipped": d.skipped,
        },
        "decision": {
            "margins": d.decision.margins,
            "left_above_noise": d.decision.left_structure,
            "rejected": (
                {
                    "effect": d.decision.rejected.fit.name,
                    "params": d.decision.rejected.fit.params,
                    "score": d.decision.rejected.score.combined_gain,
                    "because": d.decision.rejected.reasons(),
                }
                if d.decision.rejected
                else None
            ),
            "untied_from": (
                {"effect": d.decision.untied_from.fit.name, "score": d.decision.untied_from.score.combined_gain}
                if d.decision.untied_from
                else None
            ),
        },
        "causes": causes_json(d),
        "remainder": remainder_json(d),
        "discovered": d.discovered,
        "separation": d.separation.to_json() if d.separation else None,
        "declared_build": d.declared_build.to_json() if d.declared_build else None,
        "warnings": [f.to_json() for f in d.warnings] + d.data_notes,
        "verdict": verdict(d),
        "timing_s": d.seconds,
    }
    return report


def undetermined_json(fit: Fit) -> dict:
    """The fitted values the data do not determine (identify.py): each with the values it trades
    against and why, in words. Their interval is their search interval."""
    return {
        name: {"trades_against": partners, "why": why_undetermined(partners, _at_bound(fit, name))}
        for name, partners in fit.undetermined.items()
    }


def _at_bound(fit: Fit, name: str) -> bool:
    coordinate, x = fit.coordinates.get(name, (None, None))
    return coordinate is not None and coordinate.at_bound(x) is not None


def interval_phrase(fit: Fit, name: str) -> str:
    """`name = value (95 % CI lo–hi)`, or what the data cannot tell of it."""
    value, interval = fit.params[name], fit.intervals[name]
    if name in fit.undetermined:
        why = why_undetermined(fit.undetermined[name], _at_bound(fit, name))
        return f"{name} = {value:.4g} (not determined by the data: {why})"
    shown, low, high = interval_numbers(value, *interval)
    return f"{name} = {shown} (95 % CI {low}–{high})"


def _own(params: dict, effect, count: int) -> dict:
    """One effect's entries of a fit's params or intervals (a pair's are prefixed by its name)."""
    if count == 1:
        return dict(params)
    prefix = f"{effect.name()}."
    return {k[len(prefix) :]: v for k, v in params.items() if k.startswith(prefix)}


def causes_json(d: Diagnosis) -> list[dict]:
    """Each cause present, the leading one first: its parameters and intervals (fitted with every
    cause together), the channels it changes, and its own held-out gain there and on every
    channel — over the calibrated baseline for the first, over the causes before it for the next."""
    out = []
    causes = d.decision.causes
    if not causes:
        return out
    fit = causes[-1].judgement.fit
    for position, cause in enumerate(causes):
        effect = fit.effects[position]
        own = cause.own
        channels = credited_channels(d.problem, fit, [effect])
        out.append(
            {
                "effect": cause.label,
                "params": _own(fit.params, effect, len(fit.effects)),
                "intervals": {k: list(v) for k, v in _own(fit.intervals, effect, len(fit.effects)).items()},
                "channels": channels,
                "gain_own_channels": own.credited_gain,
                "gain_own_channels_ci95": own.credited_ci95,
                "gain_all_channels": own.combined_gain,
                "gain_all_channels_ci95": own.combined_ci95,
                "gain": own.gain,
                "gain_ci95": own.gain_ci95,
                "over": "baseline" if position == 0 else "+".join(c.label for c in causes[:position]),
                "base_model_strain": [f.to_json() for f in cause.judgement.strain],
            }
        )
    return out


def remainder_json(d: Diagnosis) -> dict | None:
    """What is still above the noise after the causes: each such channel's held-out RMSE over its
    noise, and the term sparse regression finds in the furthest one, with its held-out gain."""
    if not d.decision.left_structure:
        return None
    ratios = noise_ratios(d.problem, d.extended)
    found = d.discovered or {}
    where = {c: where_left(d.problem, d.extended, c) for c in d.decision.left_structure}
    return {
        "channels": {c: ratios[c] for c in d.decision.left_structure},
        "where": {c: w for c, w in where.items() if w},
        "over": "+".join(c.label for c in d.decision.causes) or "baseline",
        "discovered": {
            key: found[key] for key in ("channel", "equation", "terms", "gain", "gain_ci95", "error") if key in found
        },
    }


def _phrase(j: Judgement, channel: str) -> str:
    effect = j.fit.effects[0]
    options = {k: v for k, v in j.fit.params.items() if isinstance(v, str)}
    phrase = effect.signature() or effect.description().split(".")[0]
    return phrase.format(channel=options.get("channel", channel))


def _looks_unsettled(d: Diagnosis) -> str:
    """What the best candidate looks like when it gains enough and drops the BIC but its interval
    over the held-out units holds zero: a gain that rests on a few units (a braid's slack on the one
    zero-pressure plateau of a sweep) is shown, not left out."""
    best = d.candidates[0] if d.candidates else None
    if best is None or best.score.combined_gain < MIN_GAIN or -best.score.delta_bic <= MIN_BIC_DROP:
        return "no catalog effect gains significantly on the held-out units"
    p = d.problem
    channel = max(p.channels, key=lambda c: best.score.gain[c])
    low, high = best.score.combined_ci95
    held = np.unique(p.half_cycle[p.held_mask]).size
    return (
        f"it looks like {_phrase(best, channel)} ({best.fit.name} gains {best.score.combined_gain:.2f}, the BIC "
        f"down by {-best.score.delta_bic:.3g}), but its 95 % interval over the {held} held-out "
        f"{p.unit_name}s, [{low:.2f}, {high:.2f}], holds zero: some of them gain, others lose"
    )


def _error(channel: str, value: float, digits: str = ".3g") -> str:
    """An error of a channel as a person reads it: in its file's unit (kPa, °C)."""
    return f"{difference_from_si(channel, value):{digits}}"


def _unit(channel: str) -> str:
    return file_unit(channel) or COLUMN_UNITS.get(channel, "")


def _sizes(d: Diagnosis, fit: Fit) -> str:
    rmse = _heldout_rmse(d, fit)
    return ", ".join(
        f"{file_name(c)} {_error(c, rmse[c])} {_unit(c)} (noise {_error(c, d.problem.sigma[c], '.2g')})"
        for c in d.problem.channels
    )


def verdict(d: Diagnosis | TableDiagnosis | SeriesCampaign) -> str:
    """One sentence a person reads in ten seconds."""
    if isinstance(d, TableDiagnosis):
        return table_report.verdict(d)
    if isinstance(d, SeriesCampaign):
        return campaign.verdict(d)
    p = d.problem
    baseline_rmse = _heldout_rmse(d, d.baseline)
    decision = d.decision
    in_baseline = [f for f in d.warnings if f.parameter in d.baseline.coordinates]
    straining = [f.sentence() for f in in_baseline if not f.costs_nothing]
    resting = [f.sentence() for f in in_baseline if f.costs_nothing]
    bounds = f"; the base model strains to fit: {'; '.join(straining)}" if straining else ""
    if resting:
        bounds += f"; at a bound that costs the fit nothing: {'; '.join(resting)}"
    # A baseline value the causes left at such a bound (decide.judge), where the baseline alone was
    # not: said, not held against them.
    at_bounds = {f.parameter for f in in_baseline}
    flat = sorted(
        {
            f.sentence()
            for c in decision.causes
            for f in c.judgement.strain
            if f.costs_nothing and f.parameter not in at_bounds
        }
    )
    if flat:
        bounds += f"; with {decision.causes[0].label}, at a bound that costs the fit nothing: {'; '.join(flat)}"
    unknowns = [name for name in [*p.experiment.uncertain, *p.experiment.calibrate] if name in d.baseline.intervals]
    if unknowns:
        bounds += "; calibrated " + ", ".join(interval_phrase(d.baseline, name) for name in unknowns)
    bounds += d.data_clause
    if decision.cause == "none":
        best = d.candidates[0] if d.candidates else None
        if decision.rejected is not None:
            j = decision.rejected
            tail = f"; best candidate {j.fit.name} gains {j.score.combined_gain:.3f} but {'; '.join(j.reasons())}"
        elif best is not None:
            tail = (
                f"; best candidate {best.fit.name} gains {best.score.combined_gain:.3f} (a cause needs "
                f"{MIN_GAIN:.2f} with its 95 % CI above 0 and the BIC down by 10)"
            )
        else:
            tail = ""
        return (
            f"no cause named: the calibrated model explains the data to within its noise (held-out RMSE "
            f"{_sizes(d, d.baseline)}){tail}{_separation_phrase(d)}{bounds}"
        )
    if decision.cause == "unexplained":
        left = ", ".join(file_name(c) for c in decision.left_structure) or "the residual"
        if decision.rejected is not None:
            j = decision.rejected
            channel = max(p.channels, key=lambda c: j.score.gain[c])
            looks = (
                f"it looks like {_phrase(j, channel)} ({j.fit.name} gains {j.score.combined_gain:.2f}), but "
                f"{'; '.join(j.reasons())}"
            )
        else:
            looks = _looks_unsettled(d)
        found = d.discovered.get("terms") if d.discovered else None
        discovered = (
            (
                f"; sparse regression finds {d.discovered['equation']} (held-out gain "
                f"{d.discovered['gain'][d.discovered['channel']]:.2f}), which resembles "
                f"{found[0]['resembles']}"
            )
            if found
            else ""
        )
        where = (remainder_json(d) or {}).get("where", {})
        shape = "".join(f"{file_name(c)} {describe(w)}; " for c, w in where.items())
        return (
            f"unexplained: structure is left in {left} (held-out RMSE {_sizes(d, d.baseline)}); "
            f"{shape}{looks}{_separation_phrase(d)}{discovered}{bounds}"
        )
    causes = causes_json(d)
    first, lead = causes[0], decision.causes[0]
    channel = max(first["channels"], key=lambda c: first["gain"][c])
    numbers = _numbers(first["params"])
    lo, hi = first["gain_ci95"][channel]
    rmse = _heldout_rmse(d, lead.judgement.fit)[channel]
    text = (
        f"{_phrase(lead.judgement, channel)}: {first['effect']}{numbers}; held-out {file_name(channel)} RMSE "
        f"{_error(channel, baseline_rmse[channel])} → {_error(channel, rmse)} {_unit(channel)} (gain "
        f"{_gain_with_interval(first['gain'][channel], (lo, hi))})"
    )
    for more in causes[1:]:
        text += (
            f"; and {more['effect']}{_numbers(more['params'])} (its own held-out gain on {', '.join(more['channels'])} "
            f"{_gain_with_interval(more['gain_own_channels'], more['gain_own_channels_ci95'])})"
        )
    return text + _untied_phrase(d) + _remainder_phrase(d) + _separation_phrase(d) + bounds


def _over_noise(ratios: dict[str, float], channels: list[str]) -> str:
    return ", ".join(f"{ratios[c]:.1f}x the {file_name(c)} noise" for c in channels)


def _untied_phrase(d: Diagnosis) -> str:
    """A lead tied alone with another candidate, told apart beside its second (refused.tie_beside_a_second)."""
    other = d.decision.untied_from
    if other is None:
        return ""
    lead, second = d.decision.causes[0].label, d.decision.causes[1].label
    rival = other.fit.name.split("+")[0]  # a pair's label is its causes' labels joined by "+"
    return (
        f"; alone, {rival} explains the held-out units as well as {lead}, but beside {second} {lead} explains "
        f"more (gain {d.decision.named.score.combined_gain:.2f} against {other.score.combined_gain:.2f} for "
        f"{other.fit.name})"
    )


def _separation_phrase(d: Diagnosis) -> str:
    """What would tell apart what this test could not (separate.py): a tie's two candidates, a
    cause and its close rival, or an instrument's unneeded error and the model without it; the
    test, and how far apart the two models are there and on this test."""
    s = d.separation
    if s is None:
        return ""
    a, b = s.between
    shown = sorted((c for c in s.apart if s.apart[c] >= SEPARATES), key=lambda c: -s.apart[c])[:2]
    apart = f"{_over_noise(s.apart, shown)} (RMS; here {_over_noise(s.here, shown)})"
    if s.purpose == "confirm":
        lead = d.decision.causes[0].judgement
        close = (
            f"; {b} explains nearly as much ({a} explains {100 * gain_over(lead, lead.close_rival):.1f} % of what it "
            f"leaves, where a cause explains {100 * MIN_GAIN:.0f} %)"
        )
        if not s.separates:
            return close + " and no other test pamkit tried tells them apart"
        return f"{close}: to confirm {a}, {s.test_phrase()}, where their predictions differ by {apart}"
    if s.purpose == "check":
        if not s.separates:
            return f"; no test pamkit tried would show whether {a} is there"
        return f"; to check for {a}: {s.test_phrase()}, where the model with it and without it differ by {apart}"
    if not s.separates:
        largest = max((v for v in s.tried.values() if isinstance(v, float)), default=0.0)
        return (
            f"; no other test pamkit tried tells {a} from {b} (their predictions differ by at most {largest:.1f}x "
            "the noise)"
        )
    return f"; to tell {a} from {b}: {s.test_phrase()}, where their predictions differ by {apart}"


def _gain_with_interval(gain: float, interval) -> str:
    """ "0.97, 95 % CI 0.966–0.974": two decimals, more where two would print the interval's ends
    alike (a narrow interval is not a zero-width one)."""
    lo, hi = interval
    digits = 2
    while digits < 4 and f"{lo:.{digits}f}" == f"{hi:.{digits}f}":
        digits += 1
    return f"{gain:.{digits}f}, 95 % CI {lo:.{digits}f}–{hi:.{digits}f}"


def _numbers(params: dict) -> str:
    """A cause's fitted numbers as the verdict lists them after its name (', name = value, ...');
    nothing for a cause with none fitted (a braid's slack whose width no sample resolves is held)."""
    numbers = [f"{k} = {v:.3g}" for k, v in params.items() if not isinstance(v, str)]
    return ", " + ", ".join(numbers) if numbers else ""


def _remainder_phrase(d: Diagnosis) -> str:
    remainder = remainder_json(d)
    if remainder is None:
        return "; nothing is left above the noise"
    where = remainder["where"]
    left = " and ".join(
        f"{file_name(c)} at {r:.1f}x its noise" + (f" ({describe(where[c])})" if c in where else "")
        for c, r in remainder["channels"].items()
    )
    found = remainder["discovered"]
    if found.get("terms"):
        return (
            f"; still left: {left}, where sparse regression finds {found['equation']} (held-out gain "
            f"{found['gain'][found['channel']]:.2f}), which resembles {found['terms'][0]['resembles']}"
        )
    return f"; still left: {left}, which no catalog effect explains"


def figure(d: Diagnosis | TableDiagnosis | SeriesCampaign):
    """The diagnosis's figure, as `plot` writes it: a matplotlib Figure, open in pyplot."""
    if isinstance(d, TableDiagnosis):
        return table_figure.figure(d)
    if isinstance(d, SeriesCampaign):
        return campaign.figure(d)
    return series_figure(d, verdict(d))


def plot(d: Diagnosis | TableDiagnosis | SeriesCampaign, path: str | Path) -> Path:
    """The diagnosis's figure: a table's (tables/figure.py), a campaign's (series/campaign.py) or a
    time series' (figure.py), titled with its verdict."""
    if isinstance(d, TableDiagnosis):
        return table_figure.plot(d, path)
    if isinstance(d, SeriesCampaign):
        return campaign.plot(d, path)
    return plot_series(d, path, verdict(d))


def write(
    d: Diagnosis | TableDiagnosis | SeriesCampaign,
    json_path: str | Path | None = None,
    plot_path: str | Path | None = None,
) -> None:
    if json_path:
        Path(json_path).parent.mkdir(parents=True, exist_ok=True)
        Path(json_path).write_text(json.dumps(to_json(d), indent=2, default=float) + "\n")
    if plot_path:
        plot(d, plot_path)
