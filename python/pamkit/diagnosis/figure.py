"""The figure of one time series' diagnosis: measured against the calibrated baseline and the
extended model per channel, the residuals before and after, what the model leaves on the held-out
cycles against the signal that drives them (the way out and back apart), the candidates' ranking,
and, where the report names one, the two models on the test that would tell them apart."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pamkit.diagnosis.series.kinds import driving_signal
from pamkit.diagnosis.series.result import Diagnosis
from pamkit.diagnosis.series.separate import Separation
from pamkit.diagnosis.significance import MIN_GAIN
from pamkit.io.columns import COLUMN_UNITS, file_name, file_unit, value_from_si
from pamkit.plots import pyplot, save_figure


def plot_series(d: Diagnosis, path: str | Path, title: str) -> Path:
    """Draws `d` into `path` (PNG or PDF by its suffix) under `title`, the verdict."""
    return save_figure(series_figure(d, title), path, dpi=100)


def series_figure(d: Diagnosis, title: str):
    """`d`'s figure under `title`, the verdict: a matplotlib Figure, open in pyplot."""
    plt = pyplot()

    p = d.problem
    time = p.experiment.time_s
    rows = len(p.channels)
    s = d.separation
    parted = s is not None and s.separates and not s.variant.zero_reading
    figure = plt.figure(figsize=(18, 3.0 * rows + 3.2 + (2.8 if parted else 0.0)), constrained_layout=True)
    grid = figure.add_gridspec(rows + 1 + parted, 3, width_ratios=(1.0, 1.0, 0.7))
    held = p.held_mask
    driver, driven, _ = driving_signal(p.experiment)
    driven = value_from_si(driver, driven)
    # The way out (stretch, pressurise) and back of every held-out cycle, apart: a loop the model
    # lacks shows as two branches, an offset as one band off zero.
    out = held & (p.half_cycle >= 0) & (p.half_cycle % 2 == 0)
    back = held & (p.half_cycle >= 0) & (p.half_cycle % 2 == 1)
    # Unexplained, what the data look like (the verdict's "it looks like ..."), though it cannot
    # be named: drawn dashed, so that what it would explain is seen beside what is left.
    looks = d.decision.rejected.fit if d.cause == "unexplained" and d.decision.rejected is not None else None
    for i, c in enumerate(p.channels):
        # Drawn in the units a person reads (kPa, °C), as the data's file gives them.
        measured = value_from_si(c, p.measured[c])
        baseline, extended = (value_from_si(c, fit.predicted[c]) for fit in (d.baseline, d.extended))
        signal = figure.add_subplot(grid[i, 0])
        signal.plot(time, measured, color="0.55", lw=1.0, label="measured")
        signal.plot(time, baseline, color="C3", lw=0.9, label="baseline")
        if d.extended is not d.baseline:
            signal.plot(time, extended, color="C0", lw=0.9, label=f"extended ({d.extended.name})")
        for note in (n for n in d.data_notes if c in n.get("values", {})):
            glitched = value_from_si(c, np.asarray(note["values"][c]))
            signal.plot(note["time_s"][c], glitched, "x", color="C1", ms=7, label="glitch, left out")
        residual = figure.add_subplot(grid[i, 1], sharex=signal)
        residual.plot(time, measured - baseline, color="C3", lw=0.8, label="baseline")
        if d.extended is not d.baseline:
            residual.plot(time, measured - extended, color="C0", lw=0.8, label="extended")
        if looks is not None:
            residual.plot(
                time,
                measured - value_from_si(c, looks.predicted[c]),
                color="C4",
                lw=0.8,
                ls="--",
                label=f"looks like ({looks.name}), not named",
            )
        for axis in (signal, residual):
            _shade(axis, time, held)
            axis.grid(alpha=0.3)
        left = measured - extended  # the baseline's where no cause is named (extended is baseline)
        loop = figure.add_subplot(grid[i, 2])
        loop.plot(driven[out], left[out], ".", ms=2, color="C1", label="way out")
        loop.plot(driven[back], left[back], ".", ms=2, color="C2", label="way back")
        loop.axhline(0.0, color="0.4", lw=0.8)
        loop.grid(alpha=0.3)
        signal.set_ylabel(file_name(c))
        residual.set_ylabel(f"measured − model [{file_unit(c) or COLUMN_UNITS[c]}]")
        if i == 0:
            signal.legend(loc="upper right", fontsize="small")
            residual.legend(loc="upper right", fontsize="small")
            loop.legend(loc="upper right", fontsize="small", markerscale=4)
            signal.set_title("measured and predicted (held-out cycles shaded)")
            residual.set_title("residuals")
            model = "extended" if d.extended is not d.baseline else "baseline"
            loop.set_title(f"what the {model} model leaves, held out")
        if i == rows - 1:
            signal.set_xlabel("time [s]")
            residual.set_xlabel("time [s]")
            loop.set_xlabel(file_name(driver))
    ranking = figure.add_subplot(grid[rows, :])
    labels = [j.fit.name + ("" if j.credible else " (not credible)") for j in d.candidates]
    gains = [j.score.combined_gain for j in d.candidates]
    errors = np.array(
        [
            [j.score.combined_gain - j.score.combined_ci95[0], j.score.combined_ci95[1] - j.score.combined_gain]
            for j in d.candidates
        ]
    ).T
    colors = ["C0" if j.fit.name == d.extended.name else "0.6" if j.credible else "0.85" for j in d.candidates]
    ranking.bar(range(len(labels)), gains, yerr=errors if len(labels) else None, color=colors, capsize=3)
    ranking.axhline(MIN_GAIN, color="C3", ls="--", lw=1, label=f"needed to name a cause ({MIN_GAIN:.2f})")
    ranking.set_xticks(range(len(labels)))
    ranking.set_xticklabels(labels, rotation=20, ha="right", fontsize="small")
    ranking.set_ylabel("held-out gain (95 % CI)")
    ranking.set_ylim(min(-0.1, min(gains, default=0) - 0.05), 1.0)
    ranking.legend(loc="upper right", fontsize="small")
    ranking.grid(alpha=0.3, axis="y")
    if parted:
        _plot_separation(figure.add_subplot(grid[rows + 1, :]), s)
    figure.suptitle(title, fontsize="medium", wrap=True)
    return figure


def _plot_separation(axis, s: Separation) -> None:
    """The two models of a tie (or a cause and its close rival) on the test that parts them, on
    the channel where they differ most."""
    channel = max(s.apart, key=lambda c: s.apart[c])
    purpose = {
        "tie": f"to tell {s.between[0]} from {s.between[1]}",
        "confirm": f"to confirm {s.between[0]}",
        "check": f"to check for {s.between[0]}",
    }[s.purpose]
    for name, m, color in zip(s.between, s.predictions, ("C0", "C1")):
        axis.plot(
            np.asarray(m.time_s), value_from_si(channel, np.asarray(getattr(m, channel))), color=color, label=name
        )
    axis.set_title(f"{purpose}: {s.test_phrase()} ({s.apart[channel]:.1f}x the noise apart, RMS)")
    axis.set_xlabel("time [s]")
    axis.set_ylabel(file_name(channel))
    axis.legend(loc="upper right", fontsize="small")
    axis.grid(alpha=0.3)


def _shade(axis, time, mask):
    edges = np.flatnonzero(np.diff(np.concatenate([[0], mask.astype(int), [0]])))
    for start, end in zip(edges[::2], edges[1::2]):
        axis.axvspan(time[start], time[min(end, time.size - 1)], color="C2", alpha=0.08, lw=0)
