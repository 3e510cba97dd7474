"""Plots people would rather look at than read: SI columns in, drawn in the units a person
reads (gauge pressure in kPa, temperature in degC, lengths in mm)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pamkit._core import pressure_branches
from pamkit.io.columns import value_from_si
from pamkit.units import MILLIMETRE_PER_METRE


def pyplot():
    """matplotlib.pyplot, imported where a figure is drawn (it adds a third of a second to every
    start). A process that has not imported it yet (the command line, a batch) draws without a
    display (Agg); a session that has (a notebook, a script showing its own figures) keeps its
    backend."""
    import sys

    import matplotlib

    if "matplotlib.pyplot" not in sys.modules:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(figure, path: str | Path, dpi: int = 110) -> Path:
    """Writes `figure` to `path` (its folder made if missing), closes it and returns the path."""
    import matplotlib.pyplot as plt  # imported where a figure is drawn: it adds a third of a second to every start

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(path, dpi=dpi)
    plt.close(figure)
    return path


# Each channel with its axis label, in the unit value_from_si gives it in.
CHANNELS = (
    ("force_N", "force [N]"),
    ("gauge_pressure_Pa", "gauge pressure [kPa]"),
    ("temperature_K", "gas temperature [°C]"),
)


def plot_simulation(
    path: str | Path, predicted: dict[str, np.ndarray], measured: dict[str, np.ndarray] | None = None, title: str = ""
) -> Path:
    """Writes a 2x2 figure: force, pressure and temperature against time, and force against
    elongation (the hysteresis loop); measured channels, when given, are drawn under the
    prediction."""
    plt = pyplot()

    measured = measured or {}
    figure, axes = plt.subplots(2, 2, figsize=(11, 7.5), constrained_layout=True)
    time = predicted["time_s"]
    for axis, (name, label) in zip(axes.flat[:3], CHANNELS):
        if name in measured:
            axis.plot(measured["time_s"], value_from_si(name, measured[name]), color="0.6", lw=1.2, label="measured")
        axis.plot(time, value_from_si(name, predicted[name]), color="C0", lw=1.0, label="pamkit")
        axis.set_xlabel("time [s]")
        axis.set_ylabel(label)
        axis.grid(alpha=0.3)
        if name in measured:
            axis.legend(loc="best", fontsize="small")
    loop = axes.flat[3]
    if "force_N" in measured:
        loop.plot(
            measured["elongation_m"] * MILLIMETRE_PER_METRE, measured["force_N"], color="0.6", lw=1.2, label="measured"
        )
    loop.plot(
        predicted["elongation_m"] * MILLIMETRE_PER_METRE, predicted["force_N"], color="C0", lw=1.0, label="pamkit"
    )
    loop.set_xlabel("elongation [mm]")
    loop.set_ylabel("force [N]")
    loop.grid(alpha=0.3)
    if title:
        figure.suptitle(title)
    return save_figure(figure, path)


def plot_supplied(
    path: str | Path, predicted: dict[str, np.ndarray], measured: dict[str, np.ndarray] | None = None, title: str = ""
) -> Path:
    """A supplied-pressure test: the force against time, the supplied pressure (the model's input)
    against time, and the force against the pressure with its pressurise and vent branches apart
    (the isometric user's curve); the force against elongation only when the length moved."""
    plt = pyplot()

    measured = measured or {}
    moved = np.ptp(predicted["elongation_m"]) > 0
    figure, axes = plt.subplots(1, 4 if moved else 3, figsize=(17 if moved else 13.5, 4.6), constrained_layout=True)
    time, pressure = predicted["time_s"], value_from_si("gauge_pressure_Pa", predicted["gauge_pressure_Pa"])
    force_time, input_time, force_pressure = axes[:3]
    if "force_N" in measured:
        force_time.plot(measured["time_s"], measured["force_N"], color="0.6", lw=1.2, label="measured")
    force_time.plot(time, predicted["force_N"], color="C0", lw=1.0, label="pamkit")
    force_time.set(xlabel="time [s]", ylabel="force [N]")
    input_time.plot(time, pressure, color="k", lw=1.0)
    input_time.set(xlabel="time [s]", ylabel="supplied gauge pressure [kPa]", title="the model's input")
    branch = np.asarray(pressure_branches(predicted["gauge_pressure_Pa"]))
    for sign, name, color in ((1.0, "pressurising", "C3"), (-1.0, "venting", "C0")):
        on = np.where(branch == sign, 1.0, np.nan)  # gaps where the other branch runs
        if "force_N" in measured:
            force_pressure.plot(pressure * on, measured["force_N"] * on, ".", color=color, ms=3, alpha=0.4)
        force_pressure.plot(pressure * on, predicted["force_N"] * on, "-", color=color, lw=1.2, label=name)
    force_pressure.set(
        xlabel="supplied gauge pressure [kPa]", ylabel="force [N]", title="dots: measured; lines: pamkit"
    )
    if moved:
        loop = axes[3]
        if "force_N" in measured:
            loop.plot(
                measured["elongation_m"] * MILLIMETRE_PER_METRE,
                measured["force_N"],
                color="0.6",
                lw=1.2,
                label="measured",
            )
        loop.plot(
            predicted["elongation_m"] * MILLIMETRE_PER_METRE, predicted["force_N"], color="C0", lw=1.0, label="pamkit"
        )
        loop.set(xlabel="elongation [mm]", ylabel="force [N]")
    for axis in axes:
        axis.grid(alpha=0.3)
    force_time.legend(loc="best", fontsize="small")
    force_pressure.legend(loc="best", fontsize="small")
    if title:
        figure.suptitle(title, fontsize=9)
    return save_figure(figure, path)


def plot_table(path: str | Path, experiment, predicted: dict[str, np.ndarray], title: str = "") -> Path:
    """A static table against its supplied pressure: measured points and the prediction, one
    curve per held length of an isometric map; the length of an isotonic test in the order
    measured (its pressurise and vent branches); free length and diameter of a free-inflation
    table."""
    plt = pyplot()

    channels = {"isometric_map": ["force_N"], "isotonic": ["length_m"]}.get(experiment.kind, ["length_m", "diameter_m"])
    pressure = value_from_si("gauge_pressure_Pa", experiment.columns["gauge_pressure_Pa"])
    curves = (
        np.round(experiment.columns["length_m"], 9) if experiment.kind == "isometric_map" else np.zeros(len(pressure))
    )
    figure, axes = plt.subplots(1, len(channels), figsize=(6.5 * len(channels), 4.8), squeeze=False)
    for axis, channel in zip(axes[0], channels):
        scale, unit = (MILLIMETRE_PER_METRE, "mm") if channel.endswith("_m") else (1.0, "N")
        for curve, color in zip(np.unique(curves), plt.cm.viridis(np.linspace(0, 0.9, len(np.unique(curves))))):
            rows = np.flatnonzero(curves == curve)
            if experiment.kind != "isotonic":
                rows = rows[np.argsort(pressure[rows])]
            name = f"L = {curve * MILLIMETRE_PER_METRE:.0f} mm" if experiment.kind == "isometric_map" else "measured"
            axis.plot(pressure[rows], scale * experiment.columns[channel][rows], "o", color=color, ms=4, label=name)
            axis.plot(pressure[rows], scale * predicted[channel][rows], "-", color=color, lw=1.2)
        axis.set_xlabel("supplied pressure [kPa]")
        axis.set_ylabel(f"{channel.rsplit('_', 1)[0]} [{unit}]")
        axis.grid(alpha=0.3)
        axis.legend(fontsize=7, loc="best")
    figure.suptitle(f"{title}\npoints: measured; lines: pamkit", fontsize=9)
    figure.tight_layout()
    return save_figure(figure, path)
