"""The passive ankle exoskeleton of the thesis (chapters 4-5, appendices G.3-G.4).

The compiled core holds the gait data, linkage, clutch, springs and jig (``include/pamkit/exo``);
this module puts them together the way a designer uses them: the chapter-4 kinematics beside the
thesis's figures, the device over a gait cycle, and the muscle's ODE at walking cadence next to
the slow bench test. SI throughout; `pamkit exo` and the figure show kPa and degC.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from pamkit._core import (
    WINTER_SUBJECT_MASS_KG,
    BladderLaw,
    BraidGeometry,
    Clutch,
    ClutchMode,
    ClutchParams,
    DeviceRun,
    ElongationTrajectory,
    GaitCycle,
    GaitData,
    GaitEvents,
    GasParams,
    GasProcess,
    IdealSpring,
    Jig,
    JigParams,
    JigSample,
    LinearSpring,
    Linkage,
    LinkageParams,
    LinkagePose,
    MuscleBuild,
    MuscleModel,
    MuscleParams,
    PamStaticSpring,
    PlayParams,
    ScriptKinematics,
    Simulator,
    Table42Row,
    ThesisPolynomialSpring,
    detect_gait_events,
    fit_clutch,
    ideal_spring,
    inflated_and_sealed,
    reproduce_g3_script,
    resample_cycle,
    run_device,
    table_4_2,
    thesis_protocol,
    walking_trajectory,
    winter_appendix_g3,
    with_ankle_range,
)
from pamkit.io.columns import value_from_si
from pamkit.plots import pyplot, save_figure
from pamkit.units import MILLIMETRE_PER_METRE

GAIT_COLUMNS = ("frame", "hip_deg", "leg_deg", "foot_deg", "ankle_moment_Nm")

# What chapter 4 states, with where it states it.
THESIS_CHAPTER4 = {
    "moment_arm_m": [0.05, 0.17],  # section 4.3, figure 4.4: "fluctuated between 5 and 17 cm"
    "spring_length_m": [0.25, 0.30],  # figure 4.5 A: "varies approximately between 25 and 30 cm"
    "elongation_max_m": 0.0425,  # figure 4.5 B: "the total elongation of the spring is 4.25 cm"
    "ideal_force_N": 1000.0,  # figure 4.7 (86 kg): "approximately 1000 N with an elongation of 4 cm"
    "ideal_force_elongation_m": 0.04,
}
THESIS_BODY_MASS_KG = 86.0  # figure 4.7's subject
# The one parameter change that brings figures 4.4-4.5 out of G.3's script (docs/exo.md).
TEXT_BLOCK_ANGLE_DEG = 70.0
# Section 4.4 and table 4.1: the device is to give 25 % of the natural plantarflexion torque.
TARGET_SHARE = 0.25
# Chapter 5 (figure 5.4, section 5.3): with the device on, the wearer's ankle range fell to 15 deg.
TRIAL_ANKLE_RANGE_DEG = 15.0
# A self-selected walking cadence (not given in the thesis, whose trials report only speed,
# 1.13-1.19 m/s in table 5.2); 105 steps/min is a stride of 1.14 s.
WALKING_CADENCE_STEPS_PER_MIN = 105.0
# Section 3.2.1: the bench tests stretched at 2.5 mm/s.
BENCH_SPEED_M_PER_S = 2.5e-3


def load_winter(path: str | Path | None = None) -> GaitData:
    """Winter's walking data as printed in appendix G.3 (56.7 kg subject; built into the
    library from data/gait/winter_g3.csv), or a gait table of the same columns (frame,
    hip_deg, leg_deg, foot_deg, ankle_moment_Nm) from `path`."""
    if path is None:
        return winter_appendix_g3()
    table = np.genfromtxt(path, delimiter=",", names=True)
    missing = [c for c in GAIT_COLUMNS if c not in (table.dtype.names or ())]
    if missing:
        raise ValueError(f"{path}: missing column(s) {', '.join(missing)} (needs {', '.join(GAIT_COLUMNS)})")
    for column in GAIT_COLUMNS:
        bad = np.flatnonzero(~np.isfinite(table[column]))
        if bad.size:
            raise ValueError(f"{path}:{bad[0] + 2}: column {column} is not a number")
    return GaitData(*(np.asarray(table[c], dtype=float) for c in GAIT_COLUMNS), WINTER_SUBJECT_MASS_KG)


def winter_cycle(mass_kg: float = THESIS_BODY_MASS_KG, points: int = 690, data: GaitData | None = None) -> GaitCycle:
    """One stride of Winter's data at `points` evenly spaced percents, moment scaled to mass_kg."""
    data = data if data is not None else load_winter()
    return resample_cycle(data, detect_gait_events(data), points, mass_kg)


def _span(values) -> list[float]:
    values = np.asarray(values)
    return [float(values.min()), float(values.max())]


def chapter4(block_angle_deg: float, mass_kg: float = THESIS_BODY_MASS_KG, data: GaitData | None = None) -> dict:
    """Appendix G.3's script as printed (its rows, its engage window 12 < row < 43) with the
    block angle given and G.3's other dimensions: spring length, elongation, both moment-arm
    definitions, and the ideal spring (figure 4.7) for mass_kg."""
    data = data if data is not None else load_winter()
    linkage = Linkage(LinkageParams(block_angle_deg=block_angle_deg))
    script = reproduce_g3_script(data, linkage, mass_kg)
    stretched = np.asarray(script.elongation_m) > 0.0
    force = np.asarray(script.ideal_force_N)
    elongation = np.asarray(script.elongation_m)
    loading_end = int(np.argmax(elongation))
    at_40 = None
    if elongation[loading_end] >= THESIS_CHAPTER4["ideal_force_elongation_m"]:
        at_40 = float(
            np.interp(
                THESIS_CHAPTER4["ideal_force_elongation_m"],
                elongation[: loading_end + 1][stretched[: loading_end + 1]],
                force[: loading_end + 1][stretched[: loading_end + 1]],
            )
        )
    peak = int(np.argmax(force))
    return {
        "block_angle_deg": block_angle_deg,
        "spring_length_m": _span(script.spring_length_m),
        "elongation_max_m": float(elongation.max()),
        "moment_arm_m": _span(script.moment_arm_m),
        "horizontal_lever_m": _span(script.horizontal_lever_m),
        "ideal_force_peak_N": float(force[peak]),
        "ideal_elongation_at_peak_m": float(elongation[peak]),
        "ideal_force_at_40mm_N": at_40,
    }


def chapter4_comparison(mass_kg: float = THESIS_BODY_MASS_KG, data: GaitData | None = None) -> dict:
    """The appendix's parameters and the text's geometry side by side with chapter 4's figures."""
    data = data if data is not None else load_winter()
    return {
        "appendix_g3": chapter4(LinkageParams().block_angle_deg, mass_kg, data),
        "text_geometry": chapter4(TEXT_BLOCK_ANGLE_DEG, mass_kg, data),
        "thesis": dict(THESIS_CHAPTER4),
        "body_mass_kg": mass_kg,
    }


@dataclass
class ExoStudy:
    """Everything `pamkit exo` computes, for the report and the plot."""

    cycle: GaitCycle  # the gait the device sees (ankle range modified if asked)
    linkage: Linkage
    clutch: ClutchParams
    play: PlayParams
    spring: PamStaticSpring
    run: DeviceRun
    ideal: IdealSpring
    walking: dict | None
    report: dict


def pam_spring(
    gauge_pressure_Pa: float, build: MuscleBuild | None = None, gas: GasParams | None = None, pretension_m: float = 0.0
) -> tuple[PamStaticSpring, float]:
    """The muscle (PAM 2 of table 3.4 unless given) inflated to `gauge_pressure_Pa` [Pa] at its
    free length, sealed, isothermal (n = 1, the thesis's best fit): the static spring and that
    free length [m]."""
    params = MuscleParams(
        build=build if build is not None else MuscleBuild(),
        bladder=BladderLaw.thesis(),
        gas=gas if gas is not None else GasParams(),
    )
    start = inflated_and_sealed(params, gauge_pressure_Pa)
    spring = PamStaticSpring(
        params.build, params.bladder, params.gas, start.length_m, start.gauge_pressure_Pa, pretension_m, 1.0
    )
    return spring, start.length_m


def walking_cadence_run(
    run: DeviceRun,
    gauge_pressure_Pa: float,
    cadence_steps_per_min: float = WALKING_CADENCE_STEPS_PER_MIN,
    strides: int = 10,
    bench_cycles: int = 2,
    time_constant_s: float | None = None,
    pretension_m: float = 0.0,
) -> dict:
    """The muscle's ODE with gas-wall heat transfer, inflated to `gauge_pressure_Pa` [Pa] and
    sealed, driven by the device's elongation over `strides` strides at the cadence, and the same
    muscle stretched to the same peak on the bench (triangular cycles at 2.5 mm/s, section
    3.2.1). Returns both runs' series (SI), and a summary of each run's last stride (cycle). The
    time constant defaults to GasParams's.

    Friction is the thesis's law (eqs. 3.1.19-3.1.24) with its Kf = 1 s/m, which is nearly
    linear-viscous: fitted at 2.5 mm/s, it grows with the ~0.1 m/s of walking, so the elastic
    force (gas and bladder) is reported beside the total."""
    gas = GasParams()
    gas.process = GasProcess.heat_transfer
    if time_constant_s is not None:
        gas.heat_transfer_time_constant_s = time_constant_s
    params = MuscleParams(build=MuscleBuild(), bladder=BladderLaw.thesis(), gas=gas)
    model = MuscleModel(params, inflated_and_sealed(params, gauge_pressure_Pa))
    stride_s = 120.0 / cadence_steps_per_min  # two steps per stride
    gait = walking_trajectory(run, stride_s, strides, pretension_m)
    peak = float(np.max(gait.elongation_m))
    if not peak > 0.0:
        raise ValueError("the device never stretches the muscle, so there is no walking-cadence run to make")
    bench = thesis_protocol(peak, BENCH_SPEED_M_PER_S, bench_cycles, 0.05)
    simulator = Simulator()
    out = {
        "stride_s": stride_s,
        "cadence_steps_per_min": cadence_steps_per_min,
        "strides": strides,
        "time_constant_s": gas.heat_transfer_time_constant_s,
        "peak_elongation_m": peak,
    }
    bench_cycle_s = 2.0 * peak / BENCH_SPEED_M_PER_S
    for name, trajectory, cycle_s in (("walking", gait, stride_s), ("bench", bench, bench_cycle_s)):
        result = simulator.run(model, trajectory)
        series = {
            "time_s": np.array(result.time_s),
            "elongation_m": np.array(result.elongation_m),
            "force_N": np.array(result.force_N),
            "elastic_force_N": np.array(result.force_N) - np.array(result.friction_force_N),
            "gauge_pressure_Pa": np.array(result.gauge_pressure_Pa),
            "temperature_K": np.array(result.temperature_K),
        }
        out[name] = series
        # The last stride (cycle) once the first ones have settled the gas's mean temperature.
        last = series["time_s"] >= series["time_s"][-1] - cycle_s - 1e-9
        out[f"{name}_summary"] = {
            "peak_force_N": float(series["force_N"][last].max()),
            "peak_elastic_force_N": float(series["elastic_force_N"][last].max()),
            "min_force_N": float(series["force_N"][last].min()),
            "gauge_pressure_Pa": _span(series["gauge_pressure_Pa"][last]),
            "temperature_K": _span(series["temperature_K"][last]),
            "temperature_swing_K": float(np.ptp(series["temperature_K"][last])),
        }
    return out


def exo_study(
    mass_kg: float = THESIS_BODY_MASS_KG,
    gauge_pressure_Pa: float = 70e3,
    play_deg: float = 0.0,
    ankle_range_deg: float | None = None,
    block_angle_deg: float | None = None,
    compliance_deg_per_Nm: float = 0.0,
    clutch: ClutchParams | None = None,
    points: int = 690,
    cadence_steps_per_min: float | None = WALKING_CADENCE_STEPS_PER_MIN,
    strides: int = 10,
    time_constant_s: float | None = None,
    gait_csv: str | Path | None = None,
) -> ExoStudy:
    """The device of appendix G.3 on Winter's gait scaled to mass_kg, with the muscle inflated
    to gauge_pressure_Pa as its spring (70 kPa: the walking trials, section 4.7), the clutch's
    screws fitted to the normal gait unless given, and optionally play between leg and device
    and a reduced ankle range (chapter 5). cadence None skips the walking-cadence ODE run."""
    data = load_winter(gait_csv)
    normal = winter_cycle(mass_kg, points, data)
    clutch = clutch if clutch is not None else fit_clutch(normal)
    cycle = with_ankle_range(normal, ankle_range_deg) if ankle_range_deg is not None else normal
    params = LinkageParams() if block_angle_deg is None else LinkageParams(block_angle_deg=block_angle_deg)
    linkage = Linkage(params)
    play = PlayParams(dead_zone_deg=play_deg, compliance_deg_per_Nm=compliance_deg_per_Nm)
    spring, free_length = pam_spring(gauge_pressure_Pa)
    run = run_device(cycle, linkage, clutch, play, spring, 3)
    # The ideal spring is a property of the geometry on the normal gait, as in figure 4.7.
    normal_run = run_device(normal, linkage, clutch, PlayParams(), LinearSpring(), 3)
    ideal = ideal_spring(normal_run, normal.toe_off_percent, 1.0)
    walking = None
    if cadence_steps_per_min is not None and float(np.max(run.elongation_m)) > 0.0:
        walking = walking_cadence_run(
            run, gauge_pressure_Pa, cadence_steps_per_min, strides, time_constant_s=time_constant_s
        )
    modes = np.asarray(run.mode)
    torque = np.asarray(run.torque_Nm)
    biological = np.asarray(run.biological_torque_Nm)
    at_40 = ideal.force_at(THESIS_CHAPTER4["ideal_force_elongation_m"])
    report = {
        "inputs": {
            "mass_kg": mass_kg,
            "gauge_pressure_Pa": gauge_pressure_Pa,
            "play_deg": play_deg,
            "compliance_deg_per_Nm": compliance_deg_per_Nm,
            "ankle_range_deg": ankle_range_deg,
            "ankle_range_of_gait_deg": float(np.ptp(cycle.ankle_angle_deg)),
            "linkage": linkage.params.to_dict(),
            "clutch": clutch.to_dict(),
            "muscle_free_length_m": free_length,
        },
        "moment_arm_m": _span(run.moment_arm_m),
        "horizontal_lever_m": _span(run.horizontal_lever_m),
        "spring_length_m": _span(run.spring_length_m),
        "elongation_max_m": float(np.max(run.elongation_m)),
        "ideal_force_at_40mm_N": at_40,
        "ideal_force_peak_N": ideal.peak_force_N,
        "ideal_elongation_at_peak_m": ideal.elongation_at_peak_m,
        "peak_torque_Nm": float(torque.max()),
        "peak_biological_torque_Nm": float(biological.max()),
        "torque_share_of_biological": float(torque.max() / biological.max()),
        "target_share": TARGET_SHARE,
        "engage_pct": run.engage_percent,
        "release_pct": run.release_percent,
        "toe_off_pct": normal.toe_off_percent,
        "clutch": {
            "engage_pct": run.engage_percent,
            "release_pct": run.release_percent,
            "engaged_share_of_stride": float(np.mean(modes == int(ClutchMode.engaged))),
            "never_releases": run.release_percent is None and bool(np.all(modes != int(ClutchMode.disengaged))),
        },
        "chapter4": chapter4_comparison(THESIS_BODY_MASS_KG, data),
    }
    if walking is not None:
        report["walking"] = {
            key: walking[key]
            for key in (
                "stride_s",
                "cadence_steps_per_min",
                "strides",
                "time_constant_s",
                "peak_elongation_m",
                "walking_summary",
                "bench_summary",
            )
        }
    return ExoStudy(cycle, linkage, clutch, play, spring, run, ideal, walking, report)


def plot_exo(path: str | Path, study: ExoStudy, title: str = "") -> Path:
    """Device torque against the target share of the biological moment over the gait cycle
    with the clutch's mode shaded; and, if run, force, pressure and gas temperature of the
    muscle at walking cadence next to the slow bench test."""
    plt = pyplot()

    walking = study.walking
    rows = 2 if walking is not None else 1
    figure, axes = plt.subplots(
        rows, 3 if walking is not None else 1, figsize=(13, 4.2 * rows), constrained_layout=True, squeeze=False
    )
    run = study.run
    percent = np.asarray(run.percent)
    modes = np.asarray(run.mode)
    torque_axis = plt.subplot2grid((rows, 3), (0, 0), colspan=3, fig=figure) if walking is not None else axes[0, 0]
    if walking is not None:
        for axis in axes[0]:
            axis.remove()
    shades = {
        int(ClutchMode.engaged): ("#cfe8cf", "engaged"),
        int(ClutchMode.engaging): ("#f3e0b5", "switching"),
        int(ClutchMode.releasing): ("#f3e0b5", None),
    }
    labelled = set()
    start = 0
    for k in range(1, len(percent) + 1):
        if k == len(percent) or modes[k] != modes[start]:
            colour, label = shades.get(int(modes[start]), (None, None))
            if colour is not None:
                end = percent[k] if k < len(percent) else 100.0
                show = label if label and label not in labelled else None
                labelled.add(label)
                torque_axis.axvspan(percent[start], end, color=colour, lw=0, label=show)
            start = k
    share = study.report["target_share"]
    torque_axis.plot(
        percent, np.asarray(run.biological_torque_Nm) * share, "k--", lw=1.2, label=f"{share:.0%} of biological"
    )
    torque_axis.plot(percent, run.torque_Nm, color="C3", lw=1.5, label="device (PAM)")
    torque_axis.axvline(study.cycle.toe_off_percent, color="0.4", lw=0.8, ls=":", label="toe-off")
    torque_axis.set_xlim(0, 100)
    torque_axis.set_xlabel("gait cycle [%]")
    torque_axis.set_ylabel("plantarflexor torque [N m]")
    torque_axis.legend(loc="upper left", fontsize="small")
    torque_axis.grid(alpha=0.3)
    if walking is not None:
        for axis, (name, label) in zip(
            axes[1],
            (
                ("force_N", "force [N]"),
                ("gauge_pressure_Pa", "gauge pressure [kPa]"),
                ("temperature_K", "gas temperature [°C]"),
            ),
        ):
            for run_name, colour, text in (
                ("bench", "0.5", "bench, 2.5 mm/s"),
                ("walking", "C0", f"walking, {walking['cadence_steps_per_min']:.0f} steps/min"),
            ):
                series = walking[run_name]
                elongation_mm = series["elongation_m"] * MILLIMETRE_PER_METRE
                axis.plot(elongation_mm, value_from_si(name, series[name]), color=colour, lw=1.0, label=text)
                if name == "force_N":
                    axis.plot(
                        elongation_mm,
                        series["elastic_force_N"],
                        color=colour,
                        lw=0.8,
                        ls="--",
                        label=f"{text.split(',')[0]}: gas + bladder (no friction)",
                    )
            axis.set_xlabel("muscle elongation [mm]")
            axis.set_ylabel(label)
            axis.grid(alpha=0.3)
        axes[1, 0].legend(loc="upper left", fontsize="small")
    if title:
        figure.suptitle(title)
    return save_figure(figure, path, dpi=100)


__all__ = [
    name for name in dir() if not name.startswith("_") and name not in {"annotations", "np", "dataclass", "Path"}
]
