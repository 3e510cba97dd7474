"""pamkit log --port PORT -o OUT.csv [--duration S]"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "log",
        help="record pressure and temperature from the Arduino logger",
        description="Reads the Arduino Mega logger (firmware/pamkit_logger) on PORT and writes calibrated "
        "values to OUT.csv as they arrive (time_s, pressure_kPa gauge, temperature_C, pressure_V, "
        "temperature_V, boot, seq), flushed continuously: stop it with Ctrl-C at any time. Survives garbage, "
        "damaged frames, board resets and a pulled cable (give a /dev/serial/by-id/ name so that the port is "
        "found again), and counts each.",
    )
    parser.add_argument("--port", help="serial port: /dev/serial/by-id/..., /dev/ttyACM0, or a pty")
    parser.add_argument("-o", "--output", help="CSV file to write (an existing one only with --force)")
    parser.add_argument("--force", action="store_true", help="replace OUT.csv if it exists")
    parser.add_argument("--duration", type=float, metavar="S", help="stop after S seconds (default: until Ctrl-C)")
    parser.add_argument(
        "--calibration",
        default="logger_calibration.toml",
        metavar="TOML",
        help="calibration file (default: ./logger_calibration.toml; see --write-calibration-template)",
    )
    parser.add_argument(
        "--uncalibrated",
        action="store_true",
        help="no pressure calibration: write volts and temperature only (for calibrating)",
    )
    parser.add_argument("--baud", type=int, default=115200, help="the sketch's PAMKIT_BAUD (default: 115200)")
    parser.add_argument("--no-dtr", action="store_true", help="do not raise DTR (which resets the Mega) on open")
    parser.add_argument(
        "--banner-timeout",
        type=float,
        default=3.0,
        metavar="S",
        help="wait this long after opening for the board's banner (default: 3)",
    )
    parser.add_argument(
        "--fsync",
        type=float,
        default=1.0,
        metavar="S",
        help="make the kernel put the file on the disk at most every S seconds: what a power cut can lose "
        "(default: 1; 0: after every read; inf: leave it to the kernel). A killed or crashed pamkit log loses "
        "at most the frames of its last read (256), whatever S is",
    )
    parser.add_argument("--list", action="store_true", help="list serial ports and exit")
    parser.add_argument(
        "--write-calibration-template", metavar="TOML", help="write a calibration file to fill in and exit"
    )
    parser.set_defaults(run=run)


def _status(stats: dict, last: dict | None, rate: float, reader) -> str:
    errors = (
        f"skipped {stats['skipped_bytes']} B, crc {stats['checksum_errors']}, gaps {stats['gaps']} "
        f"({stats['missing_frames']} lost, {stats['device_dropped']} by the board), resets {stats['resets']}, "
        f"unplugged {stats['disconnects']}"
    )
    if not reader.connected:
        where = f"waiting for the port: {reader.last_error}" if reader.last_error else "waiting for the port"
        return f"{stats['seconds']:7.1f} s  {where}  | {errors}"
    values = ""
    if last:
        pressure = "" if math.isnan(last["pressure_kPa"]) else f"{last['pressure_kPa']:8.2f} kPa  "
        values = (
            f"{pressure}{last['temperature_C']:6.2f} °C  ({last['pressure_V']:.3f} V, {last['temperature_V']:.3f} V)"
        )
    return f"{stats['seconds']:7.1f} s  {rate:6.1f} Hz  {stats['rows']} rows | {errors} | {values}"


def run(arguments: argparse.Namespace) -> int:
    from pamkit._core import Error
    from pamkit._core.logger import LoggerCalibration, Reader, list_ports
    from pamkit.io.logger import CALIBRATION_TEMPLATE, LoggerError, load_calibration

    if arguments.write_calibration_template:
        path = Path(arguments.write_calibration_template)
        if path.exists():
            raise LoggerError(f"{path}: exists already; not overwriting it")
        path.write_text(CALIBRATION_TEMPLATE)
        print(f"wrote {path}: fill in measured_V (the voltage at 0, 10, ... 80 psi)")
        return 0
    if arguments.list:
        for port in list_ports():
            usb = f" USB {port['usb_vid']:04x}:{port['usb_pid']:04x}" if port["usb_vid"] >= 0 else ""
            print(f"{port['path']}  {port['description']}{usb}")
            for name in port["by_id"]:
                print(f"    {name}")
        return 0
    if not arguments.port or not arguments.output:
        raise LoggerError("--port and -o/--output are required (or --list, --write-calibration-template)")
    if arguments.duration is not None and not arguments.duration > 0:
        raise LoggerError(f"--duration {arguments.duration} must be positive")
    if not arguments.fsync >= 0:
        raise LoggerError(f"--fsync {arguments.fsync} must be >= 0 seconds (inf: never)")
    output = Path(arguments.output)
    if output.is_dir():
        raise LoggerError(f"{output}: is a folder; give a file name with -o")
    if not output.parent.is_dir():
        raise LoggerError(f"{output}: the folder {output.parent} does not exist")
    if output.exists() and not arguments.force:
        raise LoggerError(f"{output}: exists already; give --force to replace it, or another -o")

    if arguments.uncalibrated:
        calibration, calibrated = LoggerCalibration(), False
    else:
        loaded = load_calibration(arguments.calibration)
        calibration, calibrated = loaded.calibration, True
        print(
            f"calibration {arguments.calibration}: {calibration.pressure_kPa_per_V:.3f} kPa/V, "
            f"{calibration.pressure_offset_kPa:+.3f} kPa at 0 V (worst point off the line by "
            f"{loaded.max_residual_kPa:.2f} kPa); TMP36 {calibration.tmp36_offset_V} V at 0 °C, "
            f"{calibration.tmp36_V_per_C * 1e3:g} mV/°C"
        )

    live = sys.stderr.isatty()
    try:
        reader = Reader(
            arguments.port,
            arguments.output,
            calibration,
            pressure_calibrated=calibrated,
            baud=arguments.baud,
            assert_dtr=not arguments.no_dtr,
            banner_timeout_s=arguments.banner_timeout,
            fsync_interval_s=arguments.fsync,
            replace_existing=arguments.force,
        )
    except Error as error:  # the file cannot be created: the message names it and the reason
        raise LoggerError(str(error)) from None
    print(
        f"logging {arguments.port} to {arguments.output}"
        + (f" for {arguments.duration:g} s" if arguments.duration else " until Ctrl-C")
    )
    start = time.monotonic()
    last_report, report_every = start, (0.25 if live else 5.0)
    frames_at_report, banner_shown = 0, False
    interrupted, failure = False, None
    try:
        while arguments.duration is None or time.monotonic() - start < arguments.duration:
            reader.poll(0.1)
            banner = reader.banner()
            if banner and not banner_shown:
                print(
                    f"\rboard: pamkit logger {banner['firmware_version']}, {banner['rate_hz']:g} Hz, "
                    f"{banner['oversample']}x oversampling, {banner['baud']} baud",
                    file=sys.stderr,
                )
                banner_shown = True
            now = time.monotonic()
            if now - last_report >= report_every:
                stats = reader.stats()
                rate = (stats["frames"] - frames_at_report) / (now - last_report)
                frames_at_report, last_report = stats["frames"], now
                line = _status(stats, reader.last(), rate, reader)
                print(f"\r{line}\033[K" if live else line, end="" if live else "\n", file=sys.stderr, flush=True)
    except KeyboardInterrupt:
        interrupted = True
    except Error as error:  # a board with another frame format, a disk that is full: stop, say why below
        failure = str(error)
    finally:
        stats = reader.stats()
        reader.close()
    if live:
        print(file=sys.stderr)
    if stats["rows"] == 0 and not failure:
        # The file holds the header only: remove it, so that the next attempt needs no --force.
        output.unlink()
        if stats["opens"] == 0:
            reason = f"the port {arguments.port} never opened ({reader.last_error or 'no reason given'})"
        elif stats["bytes"] == 0:
            reason = f"{arguments.port} opened but sent nothing (is the logger sketch flashed and running?)"
        else:
            reason = (
                f"{arguments.port} sent {stats['bytes']} bytes but no frame (is --baud {arguments.baud} the "
                "sketch's PAMKIT_BAUD?)"
            )
        raise LoggerError(f"nothing recorded: {reason}; removed {arguments.output}, which held the header only")
    print(
        f"{'interrupted; ' if interrupted else ''}wrote {stats['rows']} rows to {arguments.output} "
        f"in {stats['seconds']:.1f} s"
    )
    print(
        f"frames {stats['frames']}, banners {stats['banners']}; garbage skipped {stats['skipped_bytes']} bytes in "
        f"{stats['resyncs']} resyncs; checksum errors {stats['checksum_errors']}; "
        f"bad banners {stats['banner_errors']}; "
        f"gaps {stats['gaps']} "
        f"({stats['missing_frames']} frames lost, {stats['device_dropped']} of them by the board); "
        f"board resets {stats['resets']}; port lost {stats['disconnects']} times; frames from before a reset dropped "
        f"{stats['stale_frames']}"
    )
    if failure:
        raise LoggerError(f"{failure} (the {stats['rows']} rows before it are in {arguments.output})")
    return 0
