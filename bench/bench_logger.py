"""Logger benchmarks (not tests):

1. decoder throughput as a multiple of the 1 Mbaud line rate (runs pamkit_bench_logger_decoder);
2. the highest sample rate the real sketch sustains without dropping a sample, at 115200 baud and
   at 1 Mbaud, measured in simavr: each firmware variant (bench/logger_firmware.cmake) runs for
   SECONDS simulated seconds while this script drains the pty; the harness counts the sequence
   gaps and the samples the firmware itself reports as dropped.

Usage:
    cmake --build build --target bench_logger_firmware pamkit_bench_logger_decoder pamkit_simavr_harness
    python bench/bench_logger.py --build build [--seconds 5]
"""

from __future__ import annotations

import argparse
import os
import re
import select
import subprocess
import tempfile
import time
import tty
from pathlib import Path


def run_variant(harness: Path, elf: Path, seconds: float) -> dict[str, float]:
    with tempfile.TemporaryDirectory() as directory:
        link, summary = Path(directory) / "tty", Path(directory) / "summary.txt"
        board = subprocess.Popen(
            [
                str(harness),
                "--firmware",
                str(elf),
                "--link",
                str(link),
                "--seconds",
                str(seconds),
                "--summary",
                str(summary),
            ],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        while not link.exists():
            time.sleep(0.005)
        fd = os.open(link, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        tty.setraw(fd, tty.TCSANOW)
        received = 0
        while not summary.exists():
            if select.select([fd], [], [], 0.1)[0]:
                try:
                    received += len(os.read(fd, 1 << 16))
                except OSError:
                    break
        os.close(fd)
        board.wait(timeout=30)
        totals = {k: float(v) for k, v in (line.split("=") for line in summary.read_text().split())}
    return totals


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build", help="CMake build directory")
    parser.add_argument("--seconds", type=float, default=5.0, help="simulated seconds per variant")
    arguments = parser.parse_args()
    build = Path(arguments.build)

    print(
        subprocess.run(
            [str(build / "bench" / "pamkit_bench_logger_decoder")], check=True, capture_output=True, text=True
        ).stdout
    )

    harness = build / "tests" / "firmware" / "pamkit_simavr_harness"
    variants = sorted(
        (build / "firmware").glob("bench_*.elf"),
        key=lambda p: [int(x) if x.isdigit() else x for x in re.split(r"(\d+)", p.stem)],
    )
    if not variants or not harness.exists():
        raise SystemExit("build the targets bench_logger_firmware and pamkit_simavr_harness first")
    print(f"sketch in simavr (ATmega2560, 16 MHz), {arguments.seconds:g} simulated s per variant:")
    print(
        f"{'baud':>8} {'rate_hz':>8} {'oversample':>10} {'frames':>7} {'expected':>8} {'gaps':>5} "
        f"{'dropped':>8}  wall_s"
    )
    best: dict[tuple[int, int], int] = {}
    for elf in variants:
        match = re.fullmatch(r"bench_(\d+)_(\d+)hz(?:_(\d+)x)?", elf.stem)
        baud, rate, oversample = int(match[1]), int(match[2]), int(match[3] or 1)
        totals = run_variant(harness, elf, arguments.seconds)
        expected = rate * arguments.seconds
        sustained = totals["seq_missing"] == 0 and totals["device_dropped"] == 0 and totals["frames"] >= 0.99 * expected
        print(
            f"{baud:>8} {rate:>8} {oversample:>10} {int(totals['frames']):>7} {int(expected):>8} "
            f"{int(totals['seq_gaps']):>5} {int(totals['device_dropped']):>8}  {totals['wall_s']:6.2f}"
            f"{'' if sustained else '  <- drops'}"
        )
        if sustained:
            best[(baud, oversample)] = max(best.get((baud, oversample), 0), rate)
    for (baud, oversample), rate in sorted(best.items()):
        print(
            f"highest rate sustained without drops at {baud} baud, {oversample}x oversampling: "
            f"{rate} Hz (of those tried)"
        )


if __name__ == "__main__":
    main()
