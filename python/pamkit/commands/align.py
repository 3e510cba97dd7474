"""pamkit align LOGGER.csv MACHINE.csv -o EXPERIMENT.toml --muscle MUSCLE.toml"""

from __future__ import annotations

import argparse
import warnings

import numpy as np

from pamkit.io.columns import LOGGER_CHANNELS, file_name, si_name, value_from_si


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "align",
        help="join a logger file and a tensile machine's export into one experiment",
        description="Finds the time offset between the Arduino logger's CSV (pamkit log) and the tensile "
        "machine's export (time, extension, load, with units in the header) by cross-correlating the "
        "logger's pressure with the machine's extension, resamples the logger onto the machine's time base over "
        "the span both recorded, and writes EXPERIMENT.toml and EXPERIMENT.csv (time_s, elongation_m, "
        "force_N, pressure_kPa gauge, temperature_C) in the format `pamkit simulate` reads.",
    )
    parser.add_argument("logger", help="CSV written by `pamkit log`")
    parser.add_argument(
        "machine",
        help="tensile machine export: Instron Bluehill's or ZwickRoell testXpert's CSV (metadata block, names "
        "row, units row; ';' and decimal commas too), or a CSV whose column names carry their units",
    )
    parser.add_argument(
        "--specimen",
        metavar="LABEL",
        help='the specimen the logger recorded, in a machine export of several (Bluehill\'s "Specimen Number"); '
        "one logger file is one specimen's test, so one is aligned at a time",
    )
    parser.add_argument("-o", "--output", required=True, help="experiment TOML to write (its CSV gets the same stem)")
    parser.add_argument(
        "--muscle",
        required=True,
        metavar="TOML",
        help="the muscle tested: a TOML with its [muscle] table (an experiment file will do; its "
        "[friction] and [gas] tables come along)",
    )
    parser.add_argument(
        "--logger-signal",
        default="pressure_kPa",
        choices=[file_name(channel) for channel in LOGGER_CHANNELS],
        help="logger channel to align on, as its CSV names it (default: pressure_kPa)",
    )
    parser.add_argument(
        "--machine-signal",
        default="extension_m",
        choices=("extension_m", "force_N"),
        help="machine channel to align on (default: extension_m: a sealed muscle's pressure follows "
        "its length without lag, while the load carries friction hysteresis)",
    )
    parser.add_argument("--max-offset", type=float, metavar="S", help="only consider offsets within ±S seconds")
    parser.add_argument(
        "--baseline",
        type=float,
        default=1.0,
        metavar="S",
        help="[test] inflation_pressure_kPa and ambient_temperature_C are the means of the logger's "
        "samples from S seconds before the joint record starts until the first stretch, at most S "
        "seconds in (default: 1)",
    )
    parser.add_argument(
        "--initial-length-m",
        type=float,
        help="[test] initial_length_m: muscle length at the start of the test (default: the free "
        "inflated length the model computes)",
    )
    parser.set_defaults(run=run)


def run(arguments: argparse.Namespace) -> int:
    from pamkit.io.logger import (
        LoggerError,
        LoggerWarning,
        align,
        read_logger_csv,
        read_machine_csv,
        read_muscle_source,
    )
    from pamkit.io.writers import write_experiment

    with warnings.catch_warnings(record=True) as dropped:
        warnings.simplefilter("always", LoggerWarning)
        logger = read_logger_csv(arguments.logger)
    for warning in dropped:
        print(f"warning: {warning.message}")
    machine = read_machine_csv(arguments.machine, arguments.specimen)
    sections = read_muscle_source(arguments.muscle)
    for name in LOGGER_CHANNELS:
        if name not in logger:
            raise LoggerError(
                f"{arguments.logger}: no {file_name(name)} column (was the log written with a calibration?)"
            )
    found = align(logger, machine, si_name(arguments.logger_signal), arguments.machine_signal, arguments.max_offset)
    offset = found.offset_s

    # the span both recorded, on the machine's time base
    t_machine = machine["time_s"]
    inside = (t_machine + offset >= logger["time_s"][0]) & (t_machine + offset <= logger["time_s"][-1])
    if inside.sum() < 2:
        raise LoggerError(
            f"after aligning (offset {offset:.3f} s) the two logs overlap in fewer than 2 machine samples"
        )
    t = t_machine[inside]
    columns = {
        "time_s": t - t[0],
        "elongation_m": machine["extension_m"][inside] - machine["extension_m"][inside][0],
        "force_N": machine["force_N"][inside],
        "gauge_pressure_Pa": np.interp(t + offset, logger["time_s"], logger["gauge_pressure_Pa"]),
        "temperature_K": np.interp(t + offset, logger["time_s"], logger["temperature_K"]),
    }
    # inflation pressure and ambient temperature: the logger's first samples of the muscle at rest,
    # inflated and not yet stretched - from `baseline` seconds before the joint record (if the logger
    # was already running) until the elongation first moves by 1 % of its range (at most `baseline` s)
    elongation = columns["elongation_m"]
    moved = np.abs(elongation) > 0.01 * np.ptp(elongation)
    still_until = columns["time_s"][np.argmax(moved)] if moved.any() else columns["time_s"][-1]
    start = t[0] + offset
    window = (logger["time_s"] >= start - arguments.baseline) & (
        logger["time_s"] <= start + min(still_until, arguments.baseline)
    )
    if not window.any():  # no logger sample at rest: take the one nearest to the start
        window = np.zeros(logger["time_s"].size, bool)
        window[np.argmin(np.abs(logger["time_s"] - start))] = True
    # [test] states them as a person reads them, in kPa and °C, to the logger's resolution.
    inflation = float(value_from_si("gauge_pressure_Pa", np.mean(logger["gauge_pressure_Pa"][window])))
    ambient = float(value_from_si("temperature_K", np.mean(logger["temperature_K"][window])))
    count = int(window.sum())
    span = (logger["time_s"][window][0] - start, logger["time_s"][window][-1] - start)
    basis = (
        f"means of the {count} logger samples from {span[0]:+.2f} s to {span[1]:+.2f} s around the start of the "
        "joint record, before the first stretch"
    )

    specimen = f" (specimen {arguments.specimen})" if arguments.specimen is not None else ""
    test = {
        "description": f"{arguments.logger} and {arguments.machine}{specimen} aligned by pamkit align: "
        "logger time = machine time "
        f"{'+' if offset >= 0 else '-'} {abs(offset):.4f} s (r = {found.correlation:.3f})",
        "inflation_pressure_kPa": round(inflation, 3),
        "ambient_temperature_C": round(ambient, 3),
        "gas": "sealed",
    }
    if arguments.initial_length_m is not None:
        test["initial_length_m"] = arguments.initial_length_m
    comments = [
        "Written by pamkit align.",
        f"logger: {arguments.logger}; machine: {arguments.machine}; muscle: {arguments.muscle} "
        f"([{'], ['.join(sections)}] copied)",
        f"time offset: logger time = machine time + {offset:.4f} s, found by cross-correlating the logger's "
        f"{file_name(found.logger_signal)} with the machine's {found.machine_signal} "
        f"(grid {found.step_s * 1e3:.3g} ms); "
        f"r = {found.correlation:.4f}; next-best cross-correlation peak {found.next_best_ratio:.3f} of the chosen one, "
        f"at {found.next_best_offset_s:.3f} s",
        f"inflation_pressure_kPa and ambient_temperature_C: {basis}",
    ]
    data = write_experiment(arguments.output, {**sections, "test": test}, columns, comments)

    print(
        f"offset: logger time = machine time {'+' if offset >= 0 else '-'} {abs(offset):.4f} s "
        f"(cross-correlation of {file_name(found.logger_signal)} with {found.machine_signal} "
        f"on a {found.step_s * 1e3:.3g} ms grid)"
    )
    print(
        f"confidence: r = {found.correlation:.4f} over the overlap at that offset; the next-best cross-correlation "
        f"peak is {found.next_best_ratio:.3f} of the chosen one (at {found.next_best_offset_s:.3f} s)"
    )
    if not found.correlation > 0.8:
        print(
            "warning: the signals correlate weakly at the best offset; check the alignment (--logger-signal, "
            "--machine-signal, --max-offset)"
        )
    if found.next_best_ratio > 0.95:
        print("warning: another offset fits almost as well (a cyclic test?); narrow it with --max-offset")
    print(
        f"[test] inflation_pressure_kPa = {test['inflation_pressure_kPa']} and ambient_temperature_C = "
        f"{test['ambient_temperature_C']}: {basis}"
    )
    print(f"wrote {arguments.output} and {data} ({len(t)} samples over {columns['time_s'][-1]:.2f} s)")
    return 0
