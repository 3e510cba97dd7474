"""The diagnosis's Jacobians from forward sensitivities against SciPy's finite differences, side by
side on the same synthetic datasets: time per diagnosis, model runs, and whether the
verdicts and gains agree.

    PYTHONPATH=build/python .venv/bin/python bench/bench_jacobians.py --datasets 39 [--json OUT]

Each dataset is diagnosed twice, the order alternating from one dataset to the next so that a
machine growing busier does not favour either. Finite differences are what the fits used before
diagnosis/series/jacobian.py: runs differenced at DIFF_STEP. Runs are counted where they are made:
plain runs (Predictor.simulate) and runs with sensitivities (one per Jacobian, each carrying a
sensitivity per coordinate that moves the model).
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import threading
import time
from contextlib import contextmanager
from pathlib import Path

import numpy as np

import pamkit.diagnosis.series.candidates as candidates
import pamkit.diagnosis.series.jacobian as jacobian
import pamkit.diagnosis.series.joint as joint
from pamkit.diagnosis import diagnose
from pamkit.diagnosis.report import to_json
from pamkit.diagnosis.series.model import Predictor
from pamkit.io.experiment import load_experiment
from pamkit.synth.dataset import hideable_effects, synthesize


@contextmanager
def counted_runs():
    """Counts plain runs and runs with sensitivities (and their sensitivities) while it lasts."""
    count = {"plain": 0, "sensitivity_runs": 0, "sensitivities": 0}
    lock = threading.Lock()
    simulate, sensitivity_jacobian = Predictor.simulate, jacobian.sensitivity_jacobian

    def counted_simulate(self, x, effects):
        with lock:
            count["plain"] += 1
        return simulate(self, x, effects)

    def counted_jacobian(problem, point, u):
        with lock:
            count["sensitivity_runs"] += 1
            count["sensitivities"] += len(u)
        return sensitivity_jacobian(problem, point, u)

    Predictor.simulate = counted_simulate
    jacobian.sensitivity_jacobian = joint.sensitivity_jacobian = counted_jacobian
    try:
        yield count
    finally:
        Predictor.simulate = simulate
        jacobian.sensitivity_jacobian = joint.sensitivity_jacobian = sensitivity_jacobian


@contextmanager
def finite_differences():
    """The fits as before sensitivities: every sealed Jacobian differences runs at DIFF_STEP (the
    fallback a fit takes where a sensitivity run fails), and the instruments' fits their one run
    at DIFF_STEP too."""
    sensitivity_jacobian, step = jacobian.sensitivity_jacobian, candidates.SENSITIVITY_STEP

    def refused(problem, point, u):
        raise RuntimeError("finite differences")

    jacobian.sensitivity_jacobian = joint.sensitivity_jacobian = refused
    candidates.SENSITIVITY_STEP = jacobian.DIFF_STEP
    try:
        yield
    finally:
        jacobian.sensitivity_jacobian = joint.sensitivity_jacobian = sensitivity_jacobian
        candidates.SENSITIVITY_STEP = step


def one_diagnosis(experiment, method: str) -> dict:
    with counted_runs() as count:
        if method == "finite differences":
            with finite_differences():
                started = time.perf_counter()
                d = diagnose(experiment)
        else:
            started = time.perf_counter()
            d = diagnose(experiment)
        seconds = time.perf_counter() - started
    report = to_json(d)
    return {
        "cause": report["cause"],
        "gain": max(report["gain"].values()) if report["gain"] else 0.0,
        "seconds": seconds,
        **count,
    }


def total(rows: list[dict], method: str) -> float:
    return sum(r[method]["seconds"] for r in rows)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--datasets", type=int, default=39)
    parser.add_argument("--first-seed", type=int, default=1000)
    parser.add_argument("--json", help="write every dataset's two diagnoses")
    arguments = parser.parse_args()

    names = ["none"] + hideable_effects()
    methods = ("sensitivities", "finite differences")
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for i in range(arguments.datasets):
            seed = arguments.first_seed + i
            files = synthesize(names[i % len(names)], seed, Path(scratch) / f"{i:04d}")
            experiment = load_experiment(files.experiment)
            row = {"seed": seed, "hidden": names[i % len(names)]}
            for method in methods if i % 2 == 0 else reversed(methods):
                row[method] = one_diagnosis(experiment, method)
            rows.append(row)
            s, f = row["sensitivities"], row["finite differences"]
            print(
                f"seed {seed}: {s['cause']:<24} {s['seconds']:5.2f} s / {f['seconds']:5.2f} s"
                + ("" if s["cause"] == f["cause"] else f"  VERDICTS DIFFER: {f['cause']} with differences"),
                file=sys.stderr,
                flush=True,
            )

    ratio = np.array([r["sensitivities"]["seconds"] / r["finite differences"]["seconds"] for r in rows])
    print(f"{len(rows)} datasets, seeds {arguments.first_seed}-{arguments.first_seed + len(rows) - 1}\n")
    print(f"{'':22s} {'sensitivities':>14s} {'fin. diff.':>11s}")
    for label, key in (("seconds, median", "seconds"), ("plain runs, median", "plain")):
        print(
            f"{label:22s} {np.median([r['sensitivities'][key] for r in rows]):14.2f} "
            f"{np.median([r['finite differences'][key] for r in rows]):11.2f}"
        )
    print(
        f"{'sensitivity runs, med.':22s} {np.median([r['sensitivities']['sensitivity_runs'] for r in rows]):14.1f} "
        f"{'0':>11s}   (carrying a median "
        f"{np.median([r['sensitivities']['sensitivities'] for r in rows]):.0f} sensitivities)"
    )
    print(
        f"\ntime ratio sensitivities / finite differences: median {np.median(ratio):.2f}, "
        f"range {ratio.min():.2f}-{ratio.max():.2f}, "
        f"total {total(rows, 'sensitivities') / total(rows, 'finite differences'):.2f}"
    )
    same = sum(r["sensitivities"]["cause"] == r["finite differences"]["cause"] for r in rows)
    gap = max(abs(r["sensitivities"]["gain"] - r["finite differences"]["gain"]) for r in rows)
    print(f"the same verdict: {same}/{len(rows)}; largest held-out gain difference {gap:.1e}")
    if arguments.json:
        Path(arguments.json).write_text(json.dumps(rows, indent=2) + "\n")
    return 0 if same == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
