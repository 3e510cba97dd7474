#!/usr/bin/env python3
"""How long a user waits before the diagnosis starts: fresh interpreters, side by side in one run.

Four commands, each in a new Python process, taking turns round by round (so load from other
processes hits all of them alike), the best of --rounds kept for each:

  import scipy.optimize      the least squares the diagnosis cannot do without: the yardstick
  import pamkit.diagnosis    everything a diagnosis imports before it starts
  pamkit diagnose --help     the command line up to its first answer (python -m pamkit)
  pamkit simulate --help     the same for the command that imports no diagnosis

It prints the ratios (import pamkit.diagnosis / import scipy.optimize, target <= 1.5;
diagnose --help / simulate --help, target about 1), in wall time and in CPU time (the child's
user + system seconds); the absolute times go to --json.

Usage:
  PYTHONPATH=build/python .venv/bin/python bench/bench_import.py [--rounds 3] [--json OUT]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

COMMANDS = {
    "import scipy.optimize": ["-c", "import scipy.optimize"],
    "import pamkit.diagnosis": ["-c", "import pamkit.diagnosis"],
    "pamkit diagnose --help": ["-m", "pamkit", "diagnose", "--help"],
    "pamkit simulate --help": ["-m", "pamkit", "simulate", "--help"],
}
RATIOS = [
    # (numerator, denominator, target)
    ("import pamkit.diagnosis", "import scipy.optimize", 1.5),
    ("pamkit diagnose --help", "pamkit simulate --help", None),
]


def environment() -> dict[str, str]:
    """The caller's environment, with the usual build directory on PYTHONPATH if pamkit is not
    importable from it."""
    env = dict(os.environ)
    probe = subprocess.run([sys.executable, "-c", "import pamkit"], env=env, capture_output=True)
    if probe.returncode != 0:
        build = os.path.join(ROOT, "build", "python")
        env["PYTHONPATH"] = os.pathsep.join(p for p in (build, env.get("PYTHONPATH")) if p)
    return env


def timed(arguments: list[str], env: dict[str, str]) -> tuple[float, float]:
    """(wall s, CPU s) of one fresh interpreter running `arguments`; the CPU time is the child's
    own user + system seconds, from the kernel's accounting of the reaped process."""
    with tempfile.TemporaryFile() as errors:
        started = time.perf_counter()
        process = subprocess.Popen([sys.executable, *arguments], env=env, stdout=subprocess.DEVNULL, stderr=errors)
        _, status, usage = os.wait4(process.pid, 0)
        wall = time.perf_counter() - started
        process.returncode = os.waitstatus_to_exitcode(status)
        if process.returncode != 0:
            errors.seek(0)
            message = errors.read().decode(errors="replace")
            raise RuntimeError(f"{' '.join(arguments)} exited with {process.returncode}: {message}")
    return wall, usage.ru_utime + usage.ru_stime


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3, help="runs of each command, taking turns (best kept)")
    parser.add_argument("--json", help="write every run's wall and CPU seconds")
    arguments = parser.parse_args()
    if arguments.rounds < 1:
        parser.error(f"--rounds: {arguments.rounds}, must be at least 1")

    env = environment()
    for name in COMMANDS:  # a warm-up each: the files in the page cache, the bytecode compiled
        timed(COMMANDS[name], env)
    runs: dict[str, list[tuple[float, float]]] = {name: [] for name in COMMANDS}
    for _ in range(arguments.rounds):
        for name, command in COMMANDS.items():
            runs[name].append(timed(command, env))
    best = {name: (min(w for w, _ in r), min(c for _, c in r)) for name, r in runs.items()}

    print(f"best of {arguments.rounds} fresh interpreters each, taking turns ({os.cpu_count()} cores)")
    print(f"{'ratio':<52} {'wall':>6} {'CPU':>6}  target")
    for numerator, denominator, target in RATIOS:
        wall = best[numerator][0] / best[denominator][0]
        cpu = best[numerator][1] / best[denominator][1]
        if target is None:
            verdict = "about 1"
        else:
            verdict = f"<= {target} — {'met' if max(wall, cpu) <= target else 'missed'}"
        print(f"{numerator + ' / ' + denominator:<52} {wall:6.2f} {cpu:6.2f}  {verdict}")
    if arguments.json:
        with open(arguments.json, "w") as out:
            json.dump({name: [{"wall_s": w, "cpu_s": c} for w, c in r] for name, r in runs.items()}, out, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
