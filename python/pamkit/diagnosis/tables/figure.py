"""The figure of a static table's diagnosis: each channel against the supplied pressure, every unit
as predicted held out (above), and what the model the verdict stands on leaves of it, held out,
against the table's noise (below): what is still left, and where."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pamkit.diagnosis.tables.engine import TableDiagnosis
from pamkit.diagnosis.tables.kinds import CYCLIC
from pamkit.io.columns import COLUMN_UNITS, value_from_si
from pamkit.io.experiment import test_names
from pamkit.plots import pyplot, save_figure
from pamkit.units import MILLIMETRE_PER_METRE

NOISE_BAND = 2.0  # the residual panels shade +-2 noise sigmas: where a model within the noise stays


def plot(d: TableDiagnosis, path: str | Path) -> Path:
    """Writes `figure(d)` to `path` (PNG or PDF by its suffix)."""
    return save_figure(figure(d), path)


def _unit(channel: str) -> tuple[float, str]:
    """The factor and unit a channel is drawn in: lengths in mm, the rest in its file unit."""
    unit = COLUMN_UNITS[channel]
    return (MILLIMETRE_PER_METRE, "mm") if unit == "m" else (1.0, unit)


def figure(d: TableDiagnosis):
    """Above, each channel against the supplied pressure: measured points, and each group as the
    calibrated baseline (dotted) and the named cause's model (solid) predicted it held out. A
    map draws one curve per held length; a free-inflation table one per test; a cyclic test its
    force against the crosshead's elongation. Below, the held-out residual of the named cause's
    model (of the baseline, with no cause) beside the band of NOISE_BAND noise sigmas. A
    matplotlib Figure, open in pyplot."""
    plt = pyplot()

    c = d.campaign
    pressure = value_from_si("gauge_pressure_Pa", c.columns["gauge_pressure_Pa"])  # drawn in kPa
    by_group = all(kind in ("isometric_map", "isotonic", CYCLIC) for kind in c.kinds)
    curves = c.groups if by_group else c.test
    names = c.group_labels if by_group else test_names(c.experiments)
    cyclic = np.isin(c.test, [i for i, kind in enumerate(c.kinds) if kind == CYCLIC])
    panels = len(d.channels) + int(cyclic.any())
    figure, axes = plt.subplots(
        2, panels, figsize=(6.5 * panels, 8.0), squeeze=False, gridspec_kw={"height_ratios": [3, 2]}
    )
    named = d.extended is not d.baseline
    left = d.extended if named else d.baseline  # the model the verdict stands on
    left_name = f"the model with {d.cause}" if named else "the calibrated baseline"
    if cyclic.any():  # at a regulated pressure: the force against the crosshead's elongation
        axis, below = axes[0][-1], axes[1][-1]
        elongation = MILLIMETRE_PER_METRE * c.columns["elongation_m"]
        for test in np.unique(c.test[cyclic]):
            rows = np.flatnonzero(c.test == test)
            label = test_names(c.experiments)[test]
            axis.plot(elongation[rows], c.columns["force_N"][rows], "o", ms=2, color="0.4", label=label)
            axis.plot(elongation[rows], d.baseline.heldout["force_N"][rows], ":", color="C0", lw=1)
            if named:
                axis.plot(elongation[rows], d.extended.heldout["force_N"][rows], "-", color="C1", lw=1.2)
            residual = c.columns["force_N"][rows] - left.heldout["force_N"][rows]
            below.plot(elongation[rows], residual, "o", ms=2, color="0.4", label=label)
        _model_axis(axis, "elongation [mm]", "force [N]")
        _residual_axis(below, d.noise["force_N"], "elongation [mm]", "force", "N", left_name)
    for axis, below, channel in zip(axes[0], axes[1], d.channels):
        scale, shown_unit = _unit(channel)
        mine = c.predicts(channel) & ~cyclic
        drawn = np.unique(curves[mine])
        # The group the remainder lies in, beyond the others' lengths: its held-out curve extrapolates;
        # a group predicted with a value only it determines: its held-out curve rests on that value.
        where = d.remainder_where.get(channel, {})
        beyond = where.get("group") if by_group and where.get("rows_beyond") else None
        resting = {c.group_labels[g]: values for g, values in d.extended.rests_on.items()} if by_group else {}
        colors = plt.cm.viridis(np.linspace(0, 0.9, len(drawn)))
        for curve, color in zip(drawn, colors):
            rows = np.flatnonzero((curves == curve) & mine)
            if c.kinds[c.test[rows[0]]] != "isotonic":  # an isotonic sweep is drawn as measured: up, down
                rows = rows[np.argsort(pressure[rows])]
            label = names[curve] + (" (held out: extrapolated)" if names[curve] == beyond else "")
            if names[curve] in resting:
                label += f" (held out: rests on {', '.join(resting[names[curve]])})"
            measured = c.columns[channel][rows]
            axis.plot(pressure[rows], scale * measured, "o", color=color, ms=4, label=label)
            axis.plot(pressure[rows], scale * d.baseline.heldout[channel][rows], ":", color=color, lw=1)
            if named:
                axis.plot(pressure[rows], scale * d.extended.heldout[channel][rows], "-", color=color, lw=1.5)
            kept = np.sort(rows[~c.censored[rows]])  # in the order measured: up one branch, down the other
            below.plot(
                pressure[kept],
                scale * (c.columns[channel][kept] - left.heldout[channel][kept]),
                "o-",
                color=color,
                ms=3,
                lw=0.8,
            )
        if (c.censored & mine).any():
            axis.plot(
                pressure[c.censored & mine],
                scale * c.columns[channel][c.censored & mine],
                "x",
                color="0.5",
                label="censored: the transducer's range end",
            )
        _model_axis(axis, "supplied pressure [kPa]", f"{channel.rsplit('_', 1)[0]} [{shown_unit}]")
        _residual_axis(
            below, scale * d.noise[channel], "supplied pressure [kPa]", channel.rsplit("_", 1)[0], shown_unit, left_name
        )
    extended = f"solid: with {d.cause}; " if named else ""
    figure.suptitle(
        f"{', '.join(test_names(c.experiments))}: cause {d.cause}\n"
        f"points: measured; dotted: calibrated baseline; {extended}\n"
        f"each {c.group_name} predicted by the model fitted without it",
        fontsize=8,
    )
    figure.tight_layout()
    return figure


def _model_axis(axis, xlabel: str, ylabel: str) -> None:
    axis.set_xlabel(xlabel)
    axis.set_ylabel(ylabel)
    axis.grid(alpha=0.3)
    axis.legend(fontsize=7, loc="best")


def _residual_axis(axis, noise: float, xlabel: str, quantity: str, unit: str, model: str) -> None:
    """A residual panel: the zero line, the band of NOISE_BAND noise sigmas, labels."""
    axis.axhspan(-NOISE_BAND * noise, NOISE_BAND * noise, color="0.85", zorder=0, label=f"±{NOISE_BAND:g} noise σ")
    axis.axhline(0.0, color="0.3", lw=0.8)
    axis.set_xlabel(xlabel)
    axis.set_ylabel(f"measured − held out [{unit}]")
    axis.set_title(f"{quantity}: what {model} leaves, held out", fontsize=8)
    axis.grid(alpha=0.3)
    axis.legend(fontsize=7, loc="best")
