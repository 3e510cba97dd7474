"""A long test: a 1 kHz bench test of 10^6 rows (about 17 minutes), synthesized,
loaded and diagnosed, with the wall time, CPU time and peak memory of every phase.

    PYTHONPATH=build/python python bench/bench_long_test.py [--rows 1000000] [--threads 2]
        [--effect none] [--seed 7] [--profile OUT.prof] [--keep DIR] [--json OUT]

The test is `pamkit synth`'s (PAM 2 on a tensile machine, an Arduino logger, the effect hidden
at a random strength) with both instruments at --rate-hz and as many triangle cycles, at the
drawn speed, as fill --rows samples. Phases are cut where diagnosis reports progress (each
message ends the phase before it), so the table is also a check that no phase runs long in
silence. CPU time counts every thread and does not depend on the machine's other load; wall
time does (the load average is printed). Peak memory is the process's high-water mark
(`ru_maxrss`) at the end of each phase: it only grows, and a phase that raised it is the one
that needed it. Target: <= 60 s and <= 1 GB in all on 2 cores, or a decimation
that the diagnosis announces.
"""

from __future__ import annotations

import argparse
import cProfile
import json
import multiprocessing
import os
import resource
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

from pamkit.diagnosis import diagnose, verdict
from pamkit.diagnosis.report import to_json
from pamkit.io.experiment import load_experiment
from pamkit.synth.dataset import Protocol, synthesize

TARGET_S = 60.0
TARGET_MB = 1024.0


def peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: kilobytes


def cpu_s() -> float:
    """CPU seconds of this process, every thread (the fits run in a pool), user and system."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


class Phases:
    """Wall time, CPU time and memory high-water mark per phase; `start(name)` ends the phase
    before. The CPU time does not depend on what else the machine runs, the wall time does."""

    def __init__(self) -> None:
        self.rows: list[tuple[str, float, float, float]] = []
        self.name: str | None = None
        self.started = 0.0
        self.cpu_started = 0.0

    def start(self, name: str) -> None:
        now, cpu = time.perf_counter(), cpu_s()
        if self.name is not None:
            self.rows.append((self.name, now - self.started, cpu - self.cpu_started, peak_mb()))
        self.name, self.started, self.cpu_started = name, now, cpu

    def stop(self) -> None:
        self.start("")
        self.name = None


def long_protocol(rows: int, rate_hz: float) -> Callable[[Protocol], Protocol]:
    """The drawn protocol with no hold, one second of rest either side, and as many cycles at
    the drawn speed and stretch as fill a test of `rows` samples at `rate_hz`."""

    def change(drawn: Protocol) -> Protocol:
        ramp_s = drawn.max_elongation_m / drawn.speed_m_per_s
        cycles = max(1, round(((rows - 1) / rate_hz - 2.0) / (2.0 * ramp_s)))
        return replace(drawn, hold_top_s=0.0, rest_before_s=1.0, rest_after_s=1.0, cycles=cycles)

    return change


def synthesize_long(arguments: argparse.Namespace, folder: Path) -> None:
    synthesize(
        arguments.effect,
        arguments.seed,
        folder,
        change_protocol=long_protocol(arguments.rows, arguments.rate_hz),
        sample_rate_Hz=arguments.rate_hz,
    )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=1_000_000)
    parser.add_argument("--rate-hz", type=float, default=1000.0)
    parser.add_argument("--effect", default="none", help="as `pamkit synth --effect`")
    parser.add_argument("--seed", type=int, default=7)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--profile", help="write a cProfile of load, diagnosis and report to this file")
    parser.add_argument("--keep", help="write the test into this folder (and reuse it if already there)")
    parser.add_argument("--json", help="write the phases and the verdict as JSON")
    arguments = parser.parse_args()

    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(arguments.keep or scratch)
        toml = folder / "experiment.toml"
        if not toml.exists():
            # In a child process, so that this one's memory high-water mark is the diagnosis's.
            made = time.perf_counter()
            child = multiprocessing.get_context("fork").Process(target=synthesize_long, args=(arguments, folder))
            child.start()
            child.join()
            if child.exitcode != 0:
                return 1
            print(f"synthesized {folder} in {time.perf_counter() - made:.1f} s", file=sys.stderr)
        phases = Phases()
        profile = cProfile.Profile() if arguments.profile else None
        if profile:
            profile.enable()
        started = time.perf_counter()
        phases.start("load CSV")
        experiment = load_experiment(toml)

        def progress(message: str) -> None:
            print(f"  {time.perf_counter() - started:7.1f} s  {message}", file=sys.stderr, flush=True)
            if not message.startswith("["):  # "[i/N] effect: ..." reports a fit done within its phase
                phases.start(message if len(message) <= 70 else message[:67] + "...")

        phases.start("diagnosis set-up")
        d = diagnose(experiment, progress=progress, threads=arguments.threads)
        phases.start("report (JSON, verdict)")
        report = to_json(d)
        sentence = verdict(d)
        phases.stop()
        total = time.perf_counter() - started
        if profile:
            profile.disable()
            profile.dump_stats(arguments.profile)

    rows = experiment.time_s.size
    print(f"\n{rows} rows read at {arguments.rate_hz:g} Hz, {arguments.threads} threads; verdict: {sentence}\n")
    print(f"{'phase':<72} {'wall s':>8} {'CPU s':>8} {'peak MB':>8}")
    for name, seconds, cpu, megabytes in phases.rows:
        print(f"{name:<72} {seconds:8.2f} {cpu:8.2f} {megabytes:8.0f}")
    peak = peak_mb()
    cpu_total = sum(row[2] for row in phases.rows)
    print(f"{'total (load, diagnosis, report)':<72} {total:8.2f} {cpu_total:8.2f} {peak:8.0f}")
    print(f"load average over the last minute at the end: {os.getloadavg()[0]:.1f} (2 cores: above 2, others ran too)")
    met = total <= TARGET_S and peak <= TARGET_MB
    print(f"\ntarget <= {TARGET_S:.0f} s and <= {TARGET_MB:.0f} MB: {'met' if met else 'MISSED'}")
    if report["warnings"]:
        print("report warnings:", *(w.get("thinned", w) for w in report["warnings"]), sep="\n  ")
    if arguments.json:
        Path(arguments.json).write_text(
            json.dumps(
                {
                    "rows": int(rows),
                    "phases": [{"phase": n, "wall_s": s, "cpu_s": c, "peak_MB": m} for n, s, c, m in phases.rows],
                    "total_s": total,
                    "cpu_s": cpu_total,
                    "peak_MB": peak,
                    "verdict": sentence,
                },
                indent=2,
            )
            + "\n"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
