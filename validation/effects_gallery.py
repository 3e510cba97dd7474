"""Writes the effect gallery of docs/effects.md: one PNG per catalog effect in docs/effects/,
and its caption (`caption`: a figure's docstring), which the documentation reads from here;
the baseline model against the model with the effect at a clearly visible strength from its
realistic range, drawn to show what gives the effect away (its signature in the catalog).
The effects are the catalog's; one without a figure of its own (`FIGURES`) is drawn by
`generic`, at its defaults, on the channels it declares.

The curves are the model's clean predictions (no instrument noise), for PAM 2 of the thesis
(pamkit.MuscleBuild's defaults) starting at its free inflated length, ambient 23 °C.

Run with pamkit importable (e.g. PYTHONPATH=build/python):  python validation/effects_gallery.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import pamkit
from pamkit.effects import catalog, parse_effects
from pamkit.io.columns import SERIES_COLUMNS, file_name, to_file, value_to_si
from pamkit.units import KELVIN_AT_ZERO_CELSIUS, PASCAL_PER_KILOPASCAL

HERE = Path(__file__).resolve().parents[1] / "docs" / "effects"  # where docs/effects.md shows them
AMBIENT_C = 23.0
SAMPLE_RATE_HZ = 20.0
BASE = {"color": "0.2", "ls": "--", "lw": 1.2}
COLORS = ("C0", "C3")


def params() -> pamkit.MuscleParams:
    gas = pamkit.GasParams()
    gas.ambient_temperature_K = AMBIENT_C + KELVIN_AT_ZERO_CELSIUS
    return pamkit.MuscleParams(
        build=pamkit.MuscleBuild(), bladder=pamkit.BladderLaw.thesis(), friction=pamkit.FrictionParams(), gas=gas
    )


def free_length(pressure_kPa: float) -> float:
    p = params()
    return pamkit.free_inflation(
        pamkit.BraidGeometry(p.build), p.bladder, p.gas.atmospheric_pressure_Pa, pressure_kPa * PASCAL_PER_KILOPASCAL
    ).length_m


def stretch(pressure_kPa: float, fraction: float) -> float:
    """`fraction` of the free contraction at this pressure [m]."""
    return fraction * (pamkit.MuscleBuild().length_m - free_length(pressure_kPa))


def corners(max_elongation_m: float, speed_m_per_s: float, cycles: int, hold_s: float = 0.0, rest_s: float = 1.0):
    """Triangle cycles (with an optional hold at the top) after a rest: corner times and elongations."""
    ramp = max_elongation_m / speed_m_per_s
    t, e = [0.0, rest_s], [0.0, 0.0]
    for _ in range(cycles):
        t += [t[-1] + ramp] + ([t[-1] + ramp + hold_s] if hold_s else [])
        e += [max_elongation_m] + ([max_elongation_m] if hold_s else [])
        t.append(t[-1] + ramp)
        e.append(0.0)
    t.append(t[-1] + rest_s)
    e.append(0.0)
    return np.asarray(t), np.asarray(e)


def simulate(pressure_kPa: float, path, specs=(), rate_Hz: float = SAMPLE_RATE_HZ) -> dict[str, np.ndarray]:
    """The model's channels along the crosshead path `path` (corners), with effects `specs`
    (`--effect` texts or configured effects), in the units the figures show (a file's:
    pressure_kPa, temperature_C)."""
    t_corner, e_corner = path
    time = np.unique(np.concatenate([np.arange(0.0, t_corner[-1], 1.0 / rate_Hz), t_corner]))
    crosshead = pamkit.ElongationTrajectory(time, np.interp(time, t_corner, e_corner))
    initial = pamkit.InitialState(
        length_m=free_length(pressure_kPa), gauge_pressure_Pa=pressure_kPa * PASCAL_PER_KILOPASCAL
    )
    effects = [spec if isinstance(spec, pamkit.Effect) else parse_effects([spec])[0] for spec in specs]
    m = pamkit.simulate_measurement(params(), initial, crosshead, effects, pamkit.Simulator())
    return to_file({name: np.asarray(getattr(m, name)) for name in SERIES_COLUMNS})


def last_cycle(run: dict[str, np.ndarray], path) -> np.ndarray:
    """Samples of the last stretch-return cycle."""
    t_corner, e_corner = path
    tops = np.flatnonzero(e_corner > 0)
    start = t_corner[tops[-1] - 1]
    return run["time_s"] >= start - 1e-9


def figure(title: str, panels: int = 2):
    fig, axes = plt.subplots(1, panels, figsize=(9.0, 3.3), constrained_layout=True)
    fig.suptitle(title, fontsize=10)
    for axis in np.atleast_1d(axes):
        axis.grid(alpha=0.3)
        axis.tick_params(labelsize=8)
    return fig, np.atleast_1d(axes)


def label(axis, x: str, y: str, legend: bool = True) -> None:
    axis.set_xlabel(x, fontsize=9)
    axis.set_ylabel(y, fontsize=9)
    if legend:
        axis.legend(fontsize=7, loc="best")


def save(fig, name: str, out_dir: Path = HERE) -> Path:
    path = out_dir / f"{name}.png"
    fig.savefig(path, dpi=80)
    plt.close(fig)
    return path


# ----------------------------------------------------------------------------------------------
# The figure of an effect that has none of its own


def generic(name: str, effect_catalog: pamkit.EffectCatalog | None = None, out_dir: Path = HERE) -> Path:
    """The effect `name` at its defaults against the baseline, over time, on the channels it
    declares it changes (force and pressure for one that acts on the muscle): a sealed stretch test
    where it acts in one, else a supplied pressure swept up and down at a held length."""
    effect = (effect_catalog if effect_catalog is not None else catalog()).make(name)
    settings = ", ".join(
        [f"{key}={value}" for key, value in effect.options().items()]
        + [f"{p.name}={p.value:g}" for p in effect.parameters()]
    )
    if effect.acts_in(pamkit.GasMode.sealed)[0]:
        channels = [file_name(c) for c in effect.channels_changed()] or ["force_N", "pressure_kPa"]
        p, e = 207.0, stretch(207.0, 0.9)
        path = corners(e, 10e-3, 2)
        base, run = simulate(p, path), simulate(p, path, [effect])
        fig, axes = figure(f"{name}: {settings} (PAM 2, 207 kPa, 90 %, 10 mm/s)", panels=len(channels))
        for axis, channel in zip(axes, channels):
            axis.plot(base["time_s"], base[channel], **BASE, label="baseline")
            axis.plot(run["time_s"], run[channel], color=COLORS[0], label=name)
            label(axis, "time [s]", channel)
    else:
        up = np.linspace(20.0, 300.0, 60)
        pressures = np.concatenate([up, up[::-1]])
        lengths = np.full_like(pressures, 0.19)
        fig, (axis,) = figure(f"{name}: {settings} (PAM 2 held at 190 mm, supplied pressure)", panels=1)
        supplied = value_to_si("pressure_kPa", pressures)
        axis.plot(pressures, pamkit.static_forces(params(), lengths, supplied), **BASE, label="baseline")
        axis.plot(pressures, pamkit.static_forces(params(), lengths, supplied, [effect]), color=COLORS[0], label=name)
        label(axis, "supplied pressure [kPa]", "force [N]")
    return save(fig, name, out_dir)


# ----------------------------------------------------------------------------------------------
# Figures drawn for what gives each effect away, where the generic one would not show it


def heat_transfer() -> Path:
    """the pressure–elongation loop opens with rate (the isothermal baseline has none), and
    after a fast stretch the pressure relaxes during the hold as the gas cools to the wall."""
    spec = "heat_transfer:time_constant_s=2"
    p, e = 207.0, stretch(207.0, 0.9)
    fig, (loops, hold) = figure(
        f"{spec} (PAM 2, 207 kPa, 90 %): pressure loops that grow with rate; pressure relaxes during a hold"
    )
    for color, speed in zip(COLORS, (2.5e-3, 25e-3)):
        path = corners(e, speed, 2)
        base, run = simulate(p, path), simulate(p, path, [spec])
        k = last_cycle(run, path)
        loops.plot(run["elongation_m"][k] * 1e3, run["pressure_kPa"][k], color=color, label=f"{speed * 1e3:g} mm/s")
    loops.plot(base["elongation_m"][k] * 1e3, base["pressure_kPa"][k], **BASE, label="baseline (any rate)")
    label(loops, "elongation [mm]", "gauge pressure [kPa]")
    path = corners(e, 25e-3, 1, hold_s=20.0)
    base, run = simulate(p, path), simulate(p, path, [spec])
    hold.plot(base["time_s"], base["pressure_kPa"], **BASE, label="baseline")
    hold.plot(run["time_s"], run["pressure_kPa"], color=COLORS[1], label="heat_transfer, 25 mm/s, 20 s hold")
    label(hold, "time [s]", "gauge pressure [kPa]")
    return save(fig, "heat_transfer")


def dead_volume() -> Path:
    """the same motion compresses a larger volume of gas, so the pressure swing, and with it the
    force, shrinks by the same factor at every rate."""
    spec = "dead_volume:volume_fraction=0.2"
    p, e = 207.0, stretch(207.0, 0.9)
    path = corners(e, 10e-3, 2)
    base, run = simulate(p, path), simulate(p, path, [spec])
    fig, (pressure, force) = figure(f"{spec} (PAM 2, 207 kPa, 90 %, 10 mm/s): the pressure swing is scaled down evenly")
    pressure.plot(
        base["time_s"], base["pressure_kPa"], **BASE, label=f"baseline, swing {np.ptp(base['pressure_kPa']):.0f} kPa"
    )
    pressure.plot(
        run["time_s"],
        run["pressure_kPa"],
        color=COLORS[0],
        label=f"dead volume, swing {np.ptp(run['pressure_kPa']):.0f} kPa",
    )
    label(pressure, "time [s]", "gauge pressure [kPa]")
    force.plot(base["elongation_m"] * 1e3, base["force_N"], **BASE, label="baseline")
    force.plot(run["elongation_m"] * 1e3, run["force_N"], color=COLORS[0], label="dead volume")
    label(force, "elongation [mm]", "force [N]")
    return save(fig, "dead_volume")


def leak() -> Path:
    """each cycle starts from less gas: the peaks drift down, fastest at high pressure."""
    spec = "leak:time_constant_s=1000"
    p, e = 207.0, stretch(207.0, 0.9)
    path = corners(e, 2.5e-3, 10)
    base, run = simulate(p, path, rate_Hz=5.0), simulate(p, path, [spec], rate_Hz=5.0)
    fig, (pressure, peaks) = figure(
        f"{spec} (PAM 2, 207 kPa, 90 %, 2.5 mm/s, 10 cycles): peaks drift down cycle after cycle"
    )
    pressure.plot(base["time_s"], base["pressure_kPa"], **BASE, label="baseline")
    pressure.plot(run["time_s"], run["pressure_kPa"], color=COLORS[1], lw=0.9, label="leak")
    label(pressure, "time [s]", "gauge pressure [kPa]")
    t_corner, e_corner = path
    tops = t_corner[np.flatnonzero(e_corner > 0)]
    for style, data, name in ((BASE, base, "baseline"), ({"color": COLORS[1], "marker": "o"}, run, "leak")):
        values = np.interp(tops, data["time_s"], data["force_N"])
        peaks.plot(np.arange(1, tops.size + 1), values, **style, label=name)
    peaks.set_xticks(range(1, tops.size + 1))
    label(peaks, "cycle", "force at the top of the stretch [N]")
    return save(fig, "leak")


def bladder_viscoelasticity() -> Path:
    """the force loop grows with rate; the bladder's share of the force, and so the effect
    relative to the force, is largest at low pressure (35 kPa, left; 276 kPa, right). The
    pressure (not shown) does not change."""
    spec = "bladder_viscoelasticity:time_constant_s=2,strength=2"
    fig, axes = figure(f"{spec}: force loops that grow with rate, strongest at low pressure")
    for axis, p in zip(axes, (35.0, 276.0)):
        e = stretch(p, 0.95)
        for color, speed in zip(COLORS, (2.5e-3, 25e-3)):
            path = corners(e, speed, 2)
            base, run = simulate(p, path), simulate(p, path, [spec])
            k = last_cycle(run, path)
            axis.plot(run["elongation_m"][k] * 1e3, run["force_N"][k], color=color, label=f"{speed * 1e3:g} mm/s")
            axis.plot(
                base["elongation_m"][k] * 1e3,
                base["force_N"][k],
                color=color,
                ls="--",
                lw=0.9,
                label=f"baseline, {speed * 1e3:g} mm/s",
            )
        axis.set_title(f"PAM 2, {p:g} kPa, 95 %", fontsize=9)
        label(axis, "elongation [mm]", "force [N]")
    return save(fig, "bladder_viscoelasticity")


def fiber_compliance() -> Path:
    """the fibers stretch under the hoop stress's pull, by T/EA: the braid is wider than the
    inextensible one at every length, the more so the higher the pressure, so the gas is
    compressed less by the same crosshead travel and force and pressure fall below the baseline,
    most at the top. The muscle's force is the virtual work of the shape with the stretched
    fibers (docs/model.md)."""
    spec = "fiber_compliance:stiffness_N=150"
    p, e = 276.0, stretch(276.0, 0.95)
    path = corners(e, 2.5e-3, 1)
    base, run = simulate(p, path), simulate(p, path, [spec])
    fig, (force, pressure) = figure(
        f"{spec} (PAM 2, 276 kPa, 95 %, 2.5 mm/s): force and pressure fall, most at the top"
    )
    force.plot(base["elongation_m"] * 1e3, base["force_N"], **BASE, label="baseline")
    force.plot(run["elongation_m"] * 1e3, run["force_N"], color=COLORS[0], label="fiber compliance")
    label(force, "crosshead elongation [mm]", "force [N]")
    pressure.plot(base["elongation_m"] * 1e3, base["pressure_kPa"], **BASE, label="baseline")
    pressure.plot(run["elongation_m"] * 1e3, run["pressure_kPa"], color=COLORS[0], label="fiber compliance")
    label(pressure, "crosshead elongation [mm]", "gauge pressure [kPa]")
    return save(fig, "fiber_compliance")


def fixture_slack() -> Path:
    """at each reversal the crosshead first takes up the play: the force stays flat for slack /
    speed (0.8 s here), then follows the baseline shifted in elongation."""
    spec = "fixture_slack:slack_m=0.002"
    p, e = 207.0, stretch(207.0, 0.9)
    path = corners(e, 2.5e-3, 2)
    base, run = simulate(p, path), simulate(p, path, [spec])
    fig, (force, loop) = figure(
        f"{spec} (PAM 2, 207 kPa, 90 %, 2.5 mm/s): force flat at the start of each stretch and return"
    )
    t_corner, e_corner = path
    turn = t_corner[3]  # the end of the first return: the start of the second stretch
    k = (base["time_s"] > turn - 3.0) & (base["time_s"] < turn + 5.0)
    force.plot(base["time_s"][k], base["force_N"][k], **BASE, label="baseline")
    force.plot(run["time_s"][k], run["force_N"][k], color=COLORS[0], label="slack")
    force.axvline(turn, color="0.6", lw=0.8)
    force.set_title("around the start of the second stretch", fontsize=9)
    label(force, "time [s]", "force [N]")
    loop.plot(base["elongation_m"] * 1e3, base["force_N"], **BASE, label="baseline")
    loop.plot(run["elongation_m"] * 1e3, run["force_N"], color=COLORS[0], label="slack")
    label(loop, "crosshead elongation [mm]", "force [N]")
    return save(fig, "fixture_slack")


def sensor_lag() -> Path:
    """the lagged channel trails the truth and its swings shrink: the pressure transducer behind
    a slow hose (left), and the TMP36 inside the muscle (right, with heat_transfer making the
    gas temperature swing), which reads a fraction of the gas's swing."""
    p, e = 207.0, stretch(207.0, 0.9)
    fig, (pressure, temperature) = figure(
        "sensor_lag: the lagged channel trails its prediction and its swings shrink (PAM 2, 207 kPa, 90 %, 25 mm/s)"
    )
    path = corners(e, 25e-3, 3)
    spec = "sensor_lag:channel=gauge_pressure_Pa,time_constant_s=1"
    base, run = simulate(p, path), simulate(p, path, [spec])
    pressure.plot(base["time_s"], base["pressure_kPa"], **BASE, label="baseline")
    pressure.plot(run["time_s"], run["pressure_kPa"], color=COLORS[0], label="channel=gauge_pressure_Pa, 1 s")
    label(pressure, "time [s]", "gauge pressure [kPa]")
    heat = "heat_transfer:time_constant_s=2"
    spec = "sensor_lag:channel=temperature_K,time_constant_s=10"
    base, run = simulate(p, path, [heat]), simulate(p, path, [heat, spec])
    temperature.plot(base["time_s"], base["temperature_C"], **BASE, label="gas (with heat_transfer, 2 s)")
    temperature.plot(run["time_s"], run["temperature_C"], color=COLORS[1], label="TMP36: channel=temperature_K, 10 s")
    label(temperature, "time [s]", "temperature [°C]")
    return save(fig, "sensor_lag")


def time_skew() -> Path:
    """the channel is shifted in time; its correlation with the prediction peaks at the skew,
    not at zero."""
    spec = "time_skew:channel=gauge_pressure_Pa,offset_s=1.5"
    p, e = 207.0, stretch(207.0, 0.9)
    path = corners(e, 10e-3, 3)
    base, run = simulate(p, path), simulate(p, path, [spec])
    fig, (pressure, correlation) = figure(f"{spec} (PAM 2, 207 kPa, 90 %, 10 mm/s): the channel is shifted in time")
    pressure.plot(base["time_s"], base["pressure_kPa"], **BASE, label="baseline")
    pressure.plot(run["time_s"], run["pressure_kPa"], color=COLORS[0], label="skewed by 1.5 s")
    label(pressure, "time [s]", "gauge pressure [kPa]")
    # Correlation of the reading with the prediction shifted by a lag: it peaks at the skew.
    dt = 1.0 / SAMPLE_RATE_HZ
    reading, prediction = run["pressure_kPa"], base["pressure_kPa"]
    lags = np.arange(-80, 81)
    values = [
        np.corrcoef(
            reading[max(lag, 0) : reading.size + min(lag, 0)], prediction[max(-lag, 0) : prediction.size - max(lag, 0)]
        )[0, 1]
        for lag in lags
    ]
    correlation.plot(lags * dt, values, color=COLORS[0])
    correlation.axvline(0.0, **BASE)
    correlation.axvline(lags[int(np.argmax(values))] * dt, color=COLORS[0], ls=":")
    label(correlation, "lag [s]", "corr(reading(t), prediction(t - lag))", legend=False)
    return save(fig, "time_skew")


def sensor_offset() -> Path:
    """the reading is a straight line of the truth: reading − prediction against the prediction
    has the offset as intercept and gain − 1 as slope."""
    spec = "sensor_offset:offset_Pa=8e3,gain=1.05"
    p, e = 207.0, stretch(207.0, 0.9)
    path = corners(e, 10e-3, 2)
    base, run = simulate(p, path), simulate(p, path, [spec])
    fig, (pressure, residual) = figure(
        f"{spec} (PAM 2, 207 kPa, 90 %, 10 mm/s): constant offset and scale in the pressure"
    )
    pressure.plot(base["time_s"], base["pressure_kPa"], **BASE, label="baseline")
    pressure.plot(run["time_s"], run["pressure_kPa"], color=COLORS[0], label="offset and gain error")
    label(pressure, "time [s]", "gauge pressure [kPa]")
    residual.plot(
        base["pressure_kPa"], run["pressure_kPa"] - base["pressure_kPa"], color=COLORS[0], marker=".", ls="none", ms=2
    )
    label(residual, "predicted gauge pressure [kPa]", "reading - prediction [kPa]", legend=False)
    return save(fig, "sensor_offset")


def load_cell() -> Path:
    """the force reading is a parabola of the truth: reading − prediction against the prediction
    has the tare as intercept and grows with the force by the nonlinearity."""
    spec = "load_cell:offset_N=-5,nonlinearity_per_kN=0.12"
    p, e = 207.0, stretch(207.0, 0.9)
    path = corners(e, 10e-3, 2)
    base, run = simulate(p, path), simulate(p, path, [spec])
    fig, (force, residual) = figure(f"{spec} (PAM 2, 207 kPa, 90 %, 10 mm/s): a tare and a share growing with F")
    force.plot(base["time_s"], base["force_N"], **BASE, label="baseline")
    force.plot(run["time_s"], run["force_N"], color=COLORS[0], label="tare and nonlinearity")
    label(force, "time [s]", "force [N]")
    residual.plot(base["force_N"], run["force_N"] - base["force_N"], color=COLORS[0], marker=".", ls="none", ms=2)
    label(residual, "predicted force [N]", "reading - prediction [N]", legend=False)
    return save(fig, "load_cell")


def braid_slack() -> Path:
    """held below its free length, the thesis's braid pushes (dashed: a negative force); a real
    braid goes slack and the load cell reads zero. It acts in supplied tests and static tables
    (an isometric map of a Festo muscle is mostly zeros at short lengths and low pressures)."""
    spec = "braid_slack:band_N=2"
    fig, axes = figure(f"{spec} (PAM 2 held at fixed lengths, supplied pressure): no push below the free length")
    for axis, pressure_kPa in zip(axes, (138.0, 276.0)):
        lengths = np.linspace(free_length(pressure_kPa) - 0.015, free_length(pressure_kPa) + 0.02, 120)
        pressures = np.full_like(lengths, value_to_si("pressure_kPa", pressure_kPa))
        base = pamkit.static_forces(params(), lengths, pressures)
        slack = pamkit.static_forces(params(), lengths, pressures, parse_effects([spec]))
        axis.plot(lengths * 1e3, base, **BASE, label="baseline (the braid pushes)")
        axis.plot(lengths * 1e3, slack, color=COLORS[0], label="braid_slack")
        axis.axhline(0.0, color="0.5", lw=0.6)
        axis.set_title(f"{pressure_kPa:.0f} kPa", fontsize=9)
        label(axis, "held length [mm]", "force [N]", legend=axis is axes[0])
    return save(fig, "braid_slack")


def pressure_hysteresis() -> Path:
    """a muscle held at one length, its supplied pressure stepped up and down: the force on
    venting lies above the force on pressurising by twice the friction; under a constant load
    (an isotonic sweep), the muscle is shorter on the way down."""
    spec = "pressure_hysteresis:coefficient=0.1"
    up = np.linspace(20.0, 300.0, 60)
    pressures = np.concatenate([up, up[::-1]])
    fig, (held, loaded) = figure(f"{spec} (PAM 2, supplied pressure raised and lowered)")
    lengths = np.full_like(pressures, 0.19)
    supplied = value_to_si("pressure_kPa", pressures)
    for specs, style in (((), BASE), ([spec], {"color": COLORS[0]})):
        force = pamkit.static_forces(params(), lengths, supplied, parse_effects(list(specs)))
        held.plot(pressures, force, **style, label=specs[0].split(":")[0] if specs else "baseline")
        path = pamkit.isotonic_lengths(params(), supplied, 60.0, params().build.length_m, parse_effects(list(specs)))
        loaded.plot(pressures, path.length_m * 1e3, **style)
    held.set_title("held at 190 mm", fontsize=9)
    loaded.set_title("under a 60 N load", fontsize=9)
    label(held, "supplied pressure [kPa]", "force [N]")
    label(loaded, "supplied pressure [kPa]", "length [mm]", legend=False)
    return save(fig, "pressure_hysteresis")


def slip_hysteresis() -> Path:
    """a DMSP-10-like muscle (fibres in its membrane, so its braid cannot push): held at its
    rest length it never moves and nothing changes; held 15 mm shorter it is slack at low
    pressure and contracts until taut, and keeps what its friction took up on the way, a
    constant less at every pressure after; under a load, settled steps up and down leave an open
    loop."""
    spec = "slip_hysteresis:slip_force_N=150,slip_distance_m=0.02"
    build = pamkit.MuscleBuild(
        length_m=0.25,
        diameter_m=0.01,
        bladder_diameter_m=0.01,
        bladder_thickness_m=0.5e-3,
        fiber_thickness_m=0.0,
        end_diameter_m=0.005,
        cone_generator_m=0.0,
        end_zone_m=0.008,
    )
    build.construction = pamkit.Construction.embedded
    build.fiber_revolutions = pamkit.fiber_revolutions_for_braid_angle(build, 22.0)
    dmsp = pamkit.MuscleParams(build=build, bladder=pamkit.BladderLaw.none())
    up = np.linspace(0.0, 600.0, 49)  # [kPa], as drawn
    fig, (held, loaded) = figure(f"{spec} (a DMSP-10-like muscle, fibres in its membrane)")
    for specs, style in (((), BASE), ([spec], {"color": COLORS[0]})):
        effects = parse_effects(list(specs))
        for length, width in ((0.25, 1.0), (0.235, 2.0)):
            force = pamkit.static_forces(dmsp, np.full_like(up, length), value_to_si("pressure_kPa", up), effects)
            held.plot(up, force, **{**style, "lw": width}, label=(specs[0].split(":")[0] if specs else "baseline"))
        sweep = np.concatenate([np.linspace(150.0, 600.0, 19), np.linspace(575.0, 150.0, 18)])
        supplied = value_to_si("pressure_kPa", sweep)
        path = pamkit.isotonic_lengths(dmsp, supplied, 120.0, dmsp.build.length_m, effects)
        loaded.plot(sweep, path.length_m * 1e3, **style)
    held.set_title("held at 250 mm (rest, thin) and 235 mm (thick)", fontsize=9)
    loaded.set_title("under 120 N, settled steps up and down", fontsize=9)
    handles, labels = held.get_legend_handles_labels()
    held.legend(handles[::2], labels[::2], fontsize=7)
    label(held, "supplied pressure [kPa]", "force [N]", legend=False)
    label(loaded, "supplied pressure [kPa]", "length [mm]", legend=False)
    return save(fig, "slip_hysteresis")


# The catalog's effects with a figure of their own; any other is drawn by `generic`.
FIGURES = {
    f.__name__: f
    for f in (
        heat_transfer,
        dead_volume,
        leak,
        bladder_viscoelasticity,
        fiber_compliance,
        fixture_slack,
        braid_slack,
        pressure_hysteresis,
        slip_hysteresis,
        sensor_lag,
        load_cell,
        time_skew,
        sensor_offset,
    )
}


def caption(name: str) -> str:
    """What the figure of the catalog effect `name` shows, for docs/effects.md: its figure's
    docstring, or for one drawn by `generic` its signature."""
    figure_of = FIGURES.get(name)
    if figure_of is not None and figure_of.__doc__:
        return " ".join(figure_of.__doc__.split())
    signature = catalog().make(name).signature().format(channel="the channel")
    return f"{signature}: the effect at its defaults against the baseline"


def draw(name: str) -> Path:
    """Writes docs/effects/NAME.png for the catalog effect `name`."""
    return FIGURES[name]() if name in FIGURES else generic(name)


def main() -> int:
    stale = sorted(set(FIGURES) - set(catalog().names()))
    if stale:
        print(f"figures for effects not in the catalog: {', '.join(stale)}", file=sys.stderr)
        return 1
    for name in catalog().names():
        path = draw(name)
        print(f"wrote {path} ({path.stat().st_size / 1e3:.0f} kB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
