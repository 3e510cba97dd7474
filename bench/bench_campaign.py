"""The thesis's 15 bench tests diagnosed as campaigns, timed against the target of the
thesis's 15 tests as one campaign in ≤ 10 s on 2 cores (docs/benchmarks.md).

    PYTHONPATH=build/python python3 bench/bench_campaign.py [--threads 2] [--time-constant 3]
        [--seed 1] [--campaigns "PAM 1,PAM 2"] [--json OUT.json]

The thesis's tests (data/experiments/thesis/pam1_*.toml: 6 tests of PAM 1; pam2_*.toml: 9 of
PAM 2) hold only their protocols. Their measured channels are written here by the independent
model of tests/independent (it never imports pamkit): each test's build from its TOML, the gas
sealed at the test's inflation pressure and initial length, its programmed elongation, one heat
exchange with the wall hidden in every test (one muscle, one wall: --time-constant), and the
bench's instruments with their noise (load cell, encoder, Arduino-logged transducer and TMP36).
A campaign is of one muscle, so the 15 tests are two campaigns, diagnosed in-process as
``pamkit diagnose A.toml B.toml ...`` diagnoses them (pamkit.diagnosis.diagnose on the list).

Printed per campaign and in total: the cause named (and whether it is the hidden one); seconds,
split into the tests' own diagnoses and the joint part (one muscle calibrated on all tests, the
effects carried from the others), and the process's CPU seconds; simulations (every model run of
the diagnosis's predictors, counted by where it was asked for, with the share of the tests' own that
are finite-difference Jacobian columns); and the ratio of the campaign's time to one simulation
of each of its tests (the sum over tests of one simulation as the diagnosis runs it, at the
test's calibrated baseline; median of --repeats). Measured on this machine: bench/README.md.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
import threading
import time
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import tomllib

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from independent import bench
from independent.families import draws, record_sealed
from independent.physics import Build, Motion, Physics, SealedMuscle

import pamkit.diagnosis.series.jacobian
import pamkit.diagnosis.series.joint
from pamkit.diagnosis import diagnose
from pamkit.diagnosis.series.model import Predictor

THESIS = Path(__file__).resolve().parents[1] / "data" / "experiments" / "thesis"
CAMPAIGNS = {"PAM 1": "pam1_*.toml", "PAM 2": "pam2_*.toml"}
HIDDEN = "heat_transfer"
# Natural convection in a 20-30 mm muscle (the catalog's heat_transfer notes, docs/table_3_6.md).
TIME_CONSTANT_S = 3.0
TARGET_S = 10.0  # the thesis's 15 tests as one campaign on 2 cores (docs/benchmarks.md)


def protocol(csv: Path) -> tuple[np.ndarray, Motion]:
    """The test's sample times and its programmed elongation as the corners it is linear between."""
    time_s, elongation_m = np.loadtxt(csv, delimiter=",", skiprows=1, unpack=True)
    slope_sign = np.sign(np.round(np.diff(elongation_m) / np.diff(time_s), 12))
    turns = np.flatnonzero(np.diff(slope_sign)) + 1
    corners = np.concatenate([[0], turns, [time_s.size - 1]])
    return time_s, Motion(time_s[corners], elongation_m[corners])


NOT_IN_THE_THESIS = ("end_zone_m", "series_compliance_m_per_N")  # build fields the thesis's muscles lack


def write_measured(toml: Path, folder: Path, physics: Physics, seed: int) -> Path:
    """The thesis test `toml` with the independent model's measured channels; its TOML's path."""
    declared = tomllib.loads(toml.read_text())
    muscle, test = declared["muscle"], declared["test"]
    time_s, motion = protocol(toml.with_name(test["data"]))
    # The thesis's muscles end in cones and are held at the crosshead: the independent model has
    # neither flat flanges' end zones nor anything in series.
    for key in NOT_IN_THE_THESIS:
        if muscle.get(key, 0.0):
            raise SystemExit(f"{toml}: {key} = {muscle[key]}; the independent thesis muscle has none")
    sealed = SealedMuscle(
        Build(**{key: value for key, value in muscle.items() if key not in NOT_IN_THE_THESIS}),
        physics,
        test["inflation_pressure_kPa"],
        test["ambient_temperature_C"],
        sealed_length_m=test["initial_length_m"],
    )
    rate_Hz = 1.0 / (time_s[1] - time_s[0])
    columns = record_sealed(sealed, motion, time_s, rate_Hz, draws(seed))
    return bench.write_experiment(
        folder,
        toml.stem,
        muscle,
        {key: value for key, value in test.items() if key != "data"},
        columns,
        f"{test['description']}; measured channels written by tests/independent (not pamkit), "
        f"{HIDDEN} hidden (time constant {physics.heat_time_constant_s} s)",
    )


@dataclass
class Simulations:
    """Every simulation the diagnosis's predictors run (on several threads), by where it was asked for."""

    tests_alone: int = 0  # each test's own diagnosis (engine, candidates, calibrate)
    finite_differences: int = 0  # of those, for a column of a finite-difference Jacobian
    campaign: int = 0  # the campaign's own: the joint calibrations and the carried effects
    sensitivity_runs: int = 0  # runs with forward sensitivities (a fit's Jacobian each), not in the counts above

    @property
    def total(self) -> int:
        return self.tests_alone + self.campaign


def _asked_by(frame) -> str:
    """`campaign` under joint.py or campaign.py, `finite_differences` under SciPy's numdiff,
    else `tests_alone` (the joint fit's own difference quotients run their simulations on pool
    threads, whose stacks do not show SciPy: they count as the campaign's)."""
    finite = False
    while frame is not None:
        name = frame.f_code.co_filename
        if name.endswith(("diagnosis/series/joint.py", "diagnosis/series/campaign.py")):
            return "campaign"
        finite = finite or name.endswith("_numdiff.py")
        frame = frame.f_back
    return "finite_differences" if finite else "tests_alone"


@contextmanager
def counting_simulations():
    """Counts every simulation the diagnosis's predictors run (Predictor.simulate: an instrument
    that reads the model's last run costs none)."""
    count = Simulations()
    lock = threading.Lock()
    simulate = Predictor.simulate

    def counted(self, x, effects):
        asked_by = _asked_by(sys._getframe(1))
        with lock:
            if asked_by == "campaign":
                count.campaign += 1
            else:
                count.tests_alone += 1
                count.finite_differences += asked_by == "finite_differences"
        return simulate(self, x, effects)

    # joint.py holds its own name for it: both are counted.
    modules = (pamkit.diagnosis.series.jacobian, pamkit.diagnosis.series.joint)
    sensitivity_jacobian = pamkit.diagnosis.series.jacobian.sensitivity_jacobian

    def counted_sensitivities(*args):
        with lock:
            count.sensitivity_runs += 1
        return sensitivity_jacobian(*args)

    Predictor.simulate = counted
    for module in modules:
        module.sensitivity_jacobian = counted_sensitivities
    try:
        yield count
    finally:
        Predictor.simulate = simulate
        for module in modules:
            module.sensitivity_jacobian = sensitivity_jacobian


def one_simulation_s(d, repeats: int) -> float:
    """Seconds of one simulation of the test as its diagnosis runs it: its calibrated baseline."""
    times = []
    for _ in range(repeats):
        started = time.perf_counter()
        d.problem.predictor.predict(d.baseline.baseline_x, [])
        times.append(time.perf_counter() - started)
    return statistics.median(times)


def run_campaign(paths: list[Path], threads: int, repeats: int) -> dict:
    joint_started = []

    def progress(message: str) -> None:  # the campaign's own part starts with this message
        if message.startswith("calibrating one muscle") and not joint_started:
            joint_started.append(time.perf_counter())

    with counting_simulations() as simulations:
        started, cpu = time.perf_counter(), time.process_time()
        c = diagnose(paths, threads=threads, progress=progress)
        seconds, cpu = time.perf_counter() - started, time.process_time() - cpu
    per_test = [
        {
            "test": name,
            "cause_alone": d.cause,
            # every cause the test names alone: beside the hidden one, a wrong name the campaign may
            # not carry but a user of that test alone would read
            "causes_alone": [cause.label for cause in d.decision.causes],
            "seconds_alone": d.seconds["total"],
            "one_simulation_s": one_simulation_s(d, repeats),
        }
        for name, d in zip(c.tests, c.diagnoses)
    ]
    one_each = sum(t["one_simulation_s"] for t in per_test)
    return {
        "tests": len(paths),
        "cause": c.cause,
        "reason": c.reason,
        "hidden_named": c.cause == HIDDEN,
        "seconds": seconds,
        "cpu_seconds": cpu,  # every thread's
        # the tests' own diagnoses run side by side: the wall time until the last is done
        "seconds_tests_alone": (joint_started[0] if joint_started else started + seconds) - started,
        "simulations": simulations.total,
        "simulations_tests_alone": simulations.tests_alone,
        "simulations_finite_differences": simulations.finite_differences,
        "simulations_campaign": simulations.campaign,
        "sensitivity_runs": simulations.sensitivity_runs,
        "one_simulation_each_s": one_each,
        "ratio": seconds / one_each,
        "shared_time_constant_s": c.extended.params.get("time_constant_s") if c.extended else None,
        "per_test": per_test,
    }


def print_tables(results: dict, total: dict) -> None:
    rows = [*results.items(), ("total", total)]
    header = (
        f"{'campaign':8s} {'tests':>5s} {'cause':14s} {'hidden?':>7s} {'seconds':>7s} {'alone':>6s} {'joint':>6s} "
        f"{'1 sim each':>10s} {'ratio':>6s} {'CPU s':>6s}"
    )
    print(header)
    print("-" * len(header))
    for name, r in rows:
        cause, hidden = (r["cause"], "yes" if r["hidden_named"] else "NO") if "cause" in r else ("", "")
        print(
            f"{name:8s} {r['tests']:5d} {cause:14s} {hidden:>7s} {r['seconds']:7.2f} {r['seconds_tests_alone']:6.2f} "
            f"{r['seconds'] - r['seconds_tests_alone']:6.2f} {r['one_simulation_each_s'] * 1e3:8.1f}ms "
            f"{r['ratio']:6.0f} {r['cpu_seconds']:6.2f}"
        )
    print(
        "  seconds: the campaign's wall time; alone: until the last of its tests' own diagnoses (run side by\n"
        "  side) is done; joint: the rest (one muscle calibrated on all tests, with the cause; effects carried);\n"
        "  ratio: seconds / (one simulation of each test); CPU s: the process's CPU time over the campaign,\n"
        "  every thread's (wall x cores it kept busy)\n"
    )
    header = (
        f"{'campaign':8s} {'simulations':>11s} {'alone':>6s} {'(fin. diff.)':>12s} {'joint':>6s} {'per test':>8s} "
        f"{'sensitivity runs':>16s}"
    )
    print(header)
    print("-" * len(header))
    for name, r in rows:
        finite = f"{r['simulations_finite_differences'] / max(r['simulations_tests_alone'], 1):.0%}"
        print(
            f"{name:8s} {r['simulations']:11d} {r['simulations_tests_alone']:6d} {finite:>12s} "
            f"{r['simulations_campaign']:6d} {r['simulations'] / r['tests']:8.0f} {r['sensitivity_runs']:16d}"
        )
    print(
        "  (fin. diff.): the share of the tests' own simulations that are finite-difference Jacobian columns;\n"
        "  sensitivity runs: runs with CVODES forward sensitivities, one per Jacobian (diagnosis/series/jacobian.py)"
    )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--threads", type=int, default=2, help="threads of each diagnosis (default 2: the machine)")
    parser.add_argument(
        "--time-constant",
        type=float,
        default=TIME_CONSTANT_S,
        help=f"hidden heat exchange [s] (default {TIME_CONSTANT_S:g})",
    )
    parser.add_argument("--seed", type=int, default=1, help="instrument noise of the first test; +1 per test")
    parser.add_argument("--repeats", type=int, default=5, help="timings of one simulation per test (median)")
    parser.add_argument("--json", help="write every campaign's numbers and each test's")
    parser.add_argument(
        "--campaigns", default=",".join(CAMPAIGNS), help=f"comma-separated, of: {', '.join(CAMPAIGNS)} (default both)"
    )
    arguments = parser.parse_args()
    chosen = [name.strip() for name in arguments.campaigns.split(",")]
    if unknown := [name for name in chosen if name not in CAMPAIGNS]:
        parser.error(f"--campaigns: no campaign {', '.join(unknown)}; there are {', '.join(CAMPAIGNS)}")
    if arguments.time_constant <= 0:
        parser.error(f"--time-constant must be > 0 s, got {arguments.time_constant:g}")
    for option in ("threads", "repeats"):
        if getattr(arguments, option) < 1:
            parser.error(f"--{option} must be at least 1, got {getattr(arguments, option)}")

    physics = Physics(heat_time_constant_s=arguments.time_constant)
    results = {}
    with tempfile.TemporaryDirectory() as scratch:
        seed = arguments.seed
        for name, pattern in CAMPAIGNS.items():
            tomls = sorted(THESIS.glob(pattern))
            if name not in chosen:  # its seeds still counted: a campaign's data do not depend on the others chosen
                seed += len(tomls)
                continue
            paths = []
            for toml in tomls:
                paths.append(write_measured(toml, Path(scratch) / toml.stem, physics, seed))
                seed += 1
            print(f"{name}: diagnosing {len(paths)} tests as one campaign", file=sys.stderr, flush=True)
            results[name] = run_campaign(paths, arguments.threads, arguments.repeats)

    total = {
        key: sum(r[key] for r in results.values())
        for key in (
            "tests",
            "seconds",
            "cpu_seconds",
            "seconds_tests_alone",
            "simulations",
            "simulations_tests_alone",
            "simulations_campaign",
            "simulations_finite_differences",
            "sensitivity_runs",
            "one_simulation_each_s",
        )
    }
    total["ratio"] = total["seconds"] / total["one_simulation_each_s"]
    print(f"hidden in every test: {HIDDEN}, time constant {arguments.time_constant:g} s; {arguments.threads} threads")
    print_tables(results, total)
    if len(results) == len(CAMPAIGNS):
        met = "met" if total["seconds"] <= TARGET_S else "MISSED"
        print(f"\ntarget: the {total['tests']} tests in ≤ {TARGET_S:g} s on 2 cores: {met} ({total['seconds']:.1f} s)")
    else:
        chosen_only = ", ".join(results)
        print(f"\ntarget: the thesis's 15 tests in ≤ {TARGET_S:g} s on 2 cores: not judged on {chosen_only} alone")
    for name, r in results.items():
        shared = r["shared_time_constant_s"]
        print(
            f"{name}: {r['cause']}: {r['reason']}"
            + (f"; shared time constant {shared:.3g} s (hidden {arguments.time_constant:g} s)" if shared else "")
        )
        print(
            "  each test alone: "
            + ", ".join(f"{t['test']} {'+'.join(t['causes_alone']) or t['cause_alone']}" for t in r["per_test"])
        )
        wrong = [t["test"] for t in r["per_test"] if set(t["causes_alone"]) - {HIDDEN}]
        print(
            f"  tests alone naming a cause not hidden: {len(wrong)} of {len(r['per_test'])}"
            + (f" ({', '.join(wrong)})" if wrong else "")
        )
    if arguments.json:
        Path(arguments.json).write_text(
            json.dumps(
                {
                    "hidden": {"effect": HIDDEN, "time_constant_s": arguments.time_constant},
                    "threads": arguments.threads,
                    "campaigns": results,
                    "total": total,
                },
                indent=2,
            )
            + "\n"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
