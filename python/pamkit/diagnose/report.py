"""The diagnosis as JSON (DESIGN.md's report keys), as a sentence, and as a figure."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from pamkit.diagnose import evidence
from pamkit.diagnose.engine import MIN_BIC_DROP, MIN_GAIN, Diagnosis, Fit

UNITS = {"force_N": "N", "pressure_kPa": "kPa", "temperature_C": "°C"}
SIGNATURES = {
    "heat_transfer": "pressure loops open up with rate and the gas exchanges heat with the wall",
    "dead_volume": "the pressure swings less than the muscle's volume change implies, evenly",
    "leak": "peaks drift down cycle after cycle",
    "bladder_viscoelasticity": "force hysteresis that pressure does not share",
    "fiber_compliance": "force softens at high stretch",
    "fixture_slack": "force stays flat at the start of each stretch",
    "sensor_lag": "{channel} lags its prediction and swings less",
    "time_skew": "{channel} is shifted in time against the machine's channels",
    "sensor_offset": "pressure reads off by a constant or a scale",
}


def _heldout_rmse(d: Diagnosis, fit: Fit) -> dict[str, float]:
    p = d.problem
    return {c: evidence.rmse((fit.predicted[c] - p.measured[c])[p.held_mask]) for c in p.channels}


def _residual_evidence(d: Diagnosis, fit: Fit) -> dict:
    p = d.problem
    time = p.experiment.time_s
    elongation = p.experiment.elongation_m
    velocity = np.gradient(elongation, time)
    regressors = {"elongation": elongation, "velocity": velocity, "abs_velocity": np.abs(velocity), "time": time,
                  "cycle": p.cycle.astype(float)}
    mask = p.held_mask
    out = {"ljung_box_p": {}, "correlation": {}, "best_lag_s": {}}
    for c in p.channels:
        r = (fit.predicted[c] - p.measured[c])[mask]
        out["ljung_box_p"][c] = evidence.ljung_box_p(r)
        out["correlation"][c] = evidence.correlations(r, {k: v[mask] for k, v in regressors.items()})
        rate = np.gradient(fit.predicted[c], time)[mask]
        out["best_lag_s"][c] = evidence.lagged_correlation_peak(r, rate, time[mask])
    return out


def to_json(d: Diagnosis) -> dict:
    """The report, with DESIGN.md's keys (and a few more: noise, evidence, verdict, timing)."""
    p = d.problem
    baseline_rmse = _heldout_rmse(d, d.baseline)
    report = {
        "baseline": {"params": d.baseline.params, "rmse": baseline_rmse},
        "candidates": [
            {
                "effect": fit.name,
                "params": fit.params,
                "heldout_rmse": s.rmse,
                "gain": s.gain,
                "gain_ci95": s.gain_ci95,
                "score": s.combined_gain,
                "score_ci95": s.combined_ci95,
                "delta_bic": s.delta_bic,
            }
            for fit, s in d.candidates
        ],
        "cause": d.cause,
        "extended": {
            "effects": [e.name() for e in d.extended.effects],
            "params": {**d.extended.baseline_params, **d.extended.params},
            "rmse": _heldout_rmse(d, d.extended),
        },
        "gain": d.extended_score.gain if d.extended_score else {c: 0.0 for c in p.channels},
        "gain_ci95": d.extended_score.gain_ci95 if d.extended_score else {c: [0.0, 0.0] for c in p.channels},
        "residuals": {"baseline": _residual_evidence(d, d.baseline), "extended": _residual_evidence(d, d.extended)},
        "evidence": {
            "noise": p.sigma,
            "peak_difference": {
                c: evidence.peak_difference(p.measured[c][p.held_mask], d.baseline.predicted[c][p.held_mask],
                                            p.cycle[p.held_mask]) for c in p.channels
            },
            "cycles": {"fitted": sorted(set(int(k) for k in p.cycle[p.fit_mask])),
                       "held_out": sorted(set(int(k) for k in p.cycle[p.held_mask]))},
            "min_gain": MIN_GAIN,
            "min_bic_drop": MIN_BIC_DROP,
            "skipped": d.skipped,
        },
        "verdict": verdict(d),
        "timing_s": d.seconds,
    }
    return report


def verdict(d: Diagnosis) -> str:
    """One sentence a person reads in ten seconds."""
    p = d.problem
    baseline_rmse = _heldout_rmse(d, d.baseline)
    if d.cause == "none":
        sizes = ", ".join(f"{c} {baseline_rmse[c]:.3g} {UNITS.get(c, '')} (noise {p.sigma[c]:.2g})" for c in p.channels)
        best = d.candidates[0] if d.candidates else None
        tail = (f"; best candidate {best[0].name} gains {best[1].combined_gain:.3f} (a cause needs {MIN_GAIN:.2f} with "
                "its 95 % CI above 0, the BIC down by 10 and parameters the sampling resolves)") if best else ""
        return f"no cause named: the calibrated model explains the data to within its noise (held-out RMSE {sizes}){tail}"
    fit, s = d.extended, d.extended_score
    channel = max(p.channels, key=lambda c: s.gain[c])
    options = {e: v for e, v in fit.params.items() if isinstance(v, str)}
    phrase = SIGNATURES.get(d.cause, fit.effects[0].description().split(".")[0]).format(channel=options.get("channel", channel))
    numbers = ", ".join(f"{k} = {v:.3g}" for k, v in fit.params.items() if not isinstance(v, str))
    lo, hi = s.gain_ci95[channel]
    unit = UNITS.get(channel, "")
    return (f"{phrase}: {fit.name}, {numbers}; held-out {channel} RMSE {baseline_rmse[channel]:.3g} → "
            f"{s.rmse[channel]:.3g} {unit} (gain {s.gain[channel]:.2f}, 95 % CI {lo:.2f}–{hi:.2f})")


def plot(d: Diagnosis, path: str | Path) -> Path:
    """Measured vs baseline vs extended per channel, residuals before and after, the ranking."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    p = d.problem
    time = p.experiment.time_s
    rows = len(p.channels)
    figure = plt.figure(figsize=(13, 3.0 * rows + 3.2), constrained_layout=True)
    grid = figure.add_gridspec(rows + 1, 2)
    held = p.held_mask
    for i, c in enumerate(p.channels):
        signal = figure.add_subplot(grid[i, 0])
        signal.plot(time, p.measured[c], color="0.55", lw=1.0, label="measured")
        signal.plot(time, d.baseline.predicted[c], color="C3", lw=0.9, label="baseline")
        if d.extended is not d.baseline:
            signal.plot(time, d.extended.predicted[c], color="C0", lw=0.9, label=f"extended ({d.extended.name})")
        residual = figure.add_subplot(grid[i, 1], sharex=signal)
        residual.plot(time, p.measured[c] - d.baseline.predicted[c], color="C3", lw=0.8, label="baseline")
        if d.extended is not d.baseline:
            residual.plot(time, p.measured[c] - d.extended.predicted[c], color="C0", lw=0.8, label="extended")
        for axis in (signal, residual):
            _shade(axis, time, held)
            axis.grid(alpha=0.3)
        signal.set_ylabel(f"{c}")
        residual.set_ylabel(f"measured − model [{UNITS.get(c, '')}]")
        if i == 0:
            signal.legend(loc="upper right", fontsize="small")
            residual.legend(loc="upper right", fontsize="small")
            signal.set_title("measured and predicted (held-out cycles shaded)")
            residual.set_title("residuals")
        if i == rows - 1:
            signal.set_xlabel("time [s]")
            residual.set_xlabel("time [s]")
    ranking = figure.add_subplot(grid[rows, :])
    labels = [fit.name for fit, _ in d.candidates]
    gains = [s.combined_gain for _, s in d.candidates]
    errors = np.array([[s.combined_gain - s.combined_ci95[0], s.combined_ci95[1] - s.combined_gain] for _, s in d.candidates]).T
    colors = ["C0" if fit.name == d.extended.name else "0.6" for fit, _ in d.candidates]
    ranking.bar(range(len(labels)), gains, yerr=errors if len(labels) else None, color=colors, capsize=3)
    ranking.axhline(MIN_GAIN, color="C3", ls="--", lw=1, label=f"needed to name a cause ({MIN_GAIN:.2f})")
    ranking.set_xticks(range(len(labels)))
    ranking.set_xticklabels(labels, rotation=20, ha="right", fontsize="small")
    ranking.set_ylabel("held-out gain (95 % CI)")
    ranking.set_ylim(min(-0.1, min(gains, default=0) - 0.05), 1.0)
    ranking.legend(loc="upper right", fontsize="small")
    ranking.grid(alpha=0.3, axis="y")
    figure.suptitle(verdict(d), fontsize="medium", wrap=True)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(path, dpi=100)
    plt.close(figure)
    return path


def _shade(axis, time, mask):
    edges = np.flatnonzero(np.diff(np.concatenate([[0], mask.astype(int), [0]])))
    for start, end in zip(edges[::2], edges[1::2]):
        axis.axvspan(time[start], time[min(end, time.size - 1)], color="C2", alpha=0.08, lw=0)


def write(d: Diagnosis, json_path: str | Path | None = None, plot_path: str | Path | None = None) -> None:
    if json_path:
        Path(json_path).parent.mkdir(parents=True, exist_ok=True)
        Path(json_path).write_text(json.dumps(to_json(d), indent=2, default=float) + "\n")
    if plot_path:
        plot(d, plot_path)
