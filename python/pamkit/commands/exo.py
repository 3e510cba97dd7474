"""pamkit exo [--mass KG] [--pressure KPA] [--play DEG] [--json OUT.json] [--plot OUT.png]"""

from __future__ import annotations

import argparse
import json

from pamkit.io.columns import value_from_si, value_to_si


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "exo",
        help="simulate the ankle exoskeleton over a gait cycle",
        description="Runs the exoskeleton of the thesis (appendix G.3's linkage, the ratchet clutch, the muscle as its "
        "spring) over Winter's gait cycle, prints the chapter-4 kinematics beside the thesis's figures, and runs the "
        "muscle at walking cadence next to the slow bench test.",
    )
    parser.add_argument(
        "--mass", type=float, default=86.0, help="body mass the gait moment is scaled to [kg] (86: figure 4.7)"
    )
    parser.add_argument(
        "--pressure", type=float, default=70.0, help="muscle inflation, gauge [kPa] (70: the walking trials)"
    )
    parser.add_argument("--play", type=float, default=0.0, help="free play between leg and device [deg]")
    parser.add_argument("--compliance", type=float, default=0.0, help="strap and shoe compliance [deg/(N m)]")
    parser.add_argument(
        "--ankle-range", type=float, help="scale the wearer's ankle range to this [deg] (chapter 5 measured 15)"
    )
    parser.add_argument("--block-angle", type=float, help="heel bar to shank on the stopper block [deg] (G.3: 100)")
    parser.add_argument("--engage-angle", type=float, help="engage screw [deg] (default: fitted to the normal gait)")
    parser.add_argument("--release-angle", type=float, help="release screw [deg] (default: fitted to the normal gait)")
    parser.add_argument("--cadence", type=float, default=105.0, help="walking cadence for the muscle run [steps/min]")
    parser.add_argument("--strides", type=int, default=10, help="strides of the walking-cadence muscle run")
    parser.add_argument(
        "--time-constant", type=float, help="gas-wall heat exchange time constant [s] (default: GasParams's)"
    )
    parser.add_argument(
        "--gait", help="gait table CSV with the columns of data/gait/winter_g3.csv (default: that table, built in)"
    )
    parser.add_argument("--json", dest="json_path", help="write the report as JSON")
    parser.add_argument("--plot", help="write a PNG: device torque over the gait cycle, and the walking-cadence run")
    parser.set_defaults(run=run)


def _describe(report: dict) -> str:
    def pct(value):
        return "never" if value is None else f"{value:.1f} %"

    c4 = report["chapter4"]
    lines = [
        f"spring length {report['spring_length_m'][0] * 100:.1f}-{report['spring_length_m'][1] * 100:.1f} cm, "
        f"elongation up to {report['elongation_max_m'] * 100:.2f} cm, moment arm "
        f"{report['moment_arm_m'][0] * 100:.1f}-{report['moment_arm_m'][1] * 100:.1f} cm",
        f"clutch: engages at {pct(report['engage_pct'])}, releases at {pct(report['release_pct'])} "
        f"(toe-off {report['toe_off_pct']:.1f} %)",
        f"peak torque {report['peak_torque_Nm']:.1f} N m = {report['torque_share_of_biological']:.0%} "
        f"of the biological "
        f"{report['peak_biological_torque_Nm']:.1f} N m (target {report['target_share']:.0%})",
        "chapter 4 (G.3 script, 86 kg): thesis | appendix parameters | block angle "
        f"{c4['text_geometry']['block_angle_deg']:.0f} deg",
    ]
    for key, label in (
        ("spring_length_m", "spring length [m]"),
        ("moment_arm_m", "perpendicular moment arm [m]"),
        ("horizontal_lever_m", "horizontal lever (G.3 momentarm(1,:)) [m]"),
    ):
        thesis = c4["thesis"]["moment_arm_m" if key == "horizontal_lever_m" else key]
        lines.append(
            f"  {label}: {thesis} | {[round(v, 4) for v in c4['appendix_g3'][key]]} | "
            f"{[round(v, 4) for v in c4['text_geometry'][key]]}"
        )
    lines.append(
        f"  elongation [m]: {c4['thesis']['elongation_max_m']} | {c4['appendix_g3']['elongation_max_m']:.4f} | "
        f"{c4['text_geometry']['elongation_max_m']:.4f}"
    )
    lines.append(
        f"  ideal force peak [N]: ~{c4['thesis']['ideal_force_N']:.0f} at 0.04 m | "
        f"{c4['appendix_g3']['ideal_force_peak_N']:.0f} at {c4['appendix_g3']['ideal_elongation_at_peak_m']:.4f} m | "
        f"{c4['text_geometry']['ideal_force_peak_N']:.0f} at {c4['text_geometry']['ideal_elongation_at_peak_m']:.4f} m"
    )
    if "walking" in report:
        w = report["walking"]
        for name in ("walking", "bench"):
            s = w[f"{name}_summary"]
            lowest, highest = (value_from_si("gauge_pressure_Pa", p) for p in s["gauge_pressure_Pa"])
            lines.append(
                f"muscle, {name} (last cycle): peak force {s['peak_force_N']:.1f} N (gas + bladder "
                f"{s['peak_elastic_force_N']:.1f} N), pressure {lowest:.1f}-{highest:.1f} kPa, "
                f"gas temperature swing {s['temperature_swing_K']:.2f} °C"
            )
    return "\n".join(lines)


def run(arguments: argparse.Namespace) -> int:
    from pamkit.exo import ClutchParams, exo_study, fit_clutch, plot_exo, winter_cycle

    clutch = None
    if arguments.engage_angle is not None or arguments.release_angle is not None:
        fitted = fit_clutch(winter_cycle(arguments.mass))
        clutch = ClutchParams(
            engage_angle_deg=arguments.engage_angle if arguments.engage_angle is not None else fitted.engage_angle_deg,
            release_angle_deg=arguments.release_angle
            if arguments.release_angle is not None
            else fitted.release_angle_deg,
        )
    print("running the device over the gait cycle and the muscle at walking cadence...", flush=True)
    study = exo_study(
        mass_kg=arguments.mass,
        gauge_pressure_Pa=value_to_si("pressure_kPa", arguments.pressure),
        play_deg=arguments.play,
        ankle_range_deg=arguments.ankle_range,
        block_angle_deg=arguments.block_angle,
        compliance_deg_per_Nm=arguments.compliance,
        clutch=clutch,
        cadence_steps_per_min=arguments.cadence,
        strides=arguments.strides,
        time_constant_s=arguments.time_constant,
        gait_csv=arguments.gait,
    )
    print(_describe(study.report))
    if arguments.json_path:
        with open(arguments.json_path, "w", encoding="utf-8") as out:
            json.dump(study.report, out, indent=2)
        print(f"wrote {arguments.json_path}")
    if arguments.plot:
        plot_exo(
            arguments.plot,
            study,
            title=f"PAM at {arguments.pressure:g} kPa, {arguments.mass:g} kg, play {arguments.play:g} deg",
        )
        print(f"wrote {arguments.plot}")
    return 0
