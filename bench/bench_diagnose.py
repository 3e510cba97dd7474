"""Diagnosis over many synthetic datasets, each with one effect hidden by `pamkit synth`: a confusion
matrix of hidden effect against named cause, the detection and false-alarm rates, the median
held-out gain, and the time per diagnosis with its breakdown.

    PYTHONPATH=build/python .venv/bin/python bench/bench_diagnose.py --datasets 200 [--json OUT]

Datasets cycle through the catalog and "none" (equal shares), seeds from --first-seed on. The
time per diagnosis is machine-dependent: the breakdown (baseline calibration, candidate fits)
and its ratio to one simulation of the same dataset are what carry over.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from collections import Counter, defaultdict
from pathlib import Path

import numpy as np

from pamkit.diagnosis import diagnose
from pamkit.diagnosis.report import to_json
from pamkit.io.experiment import load_experiment
from pamkit.simulation import simulate_experiment
from pamkit.synth.dataset import hideable_effects, synthesize
from pamkit.synth.mismatch import draw_mismatch


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--datasets", type=int, default=200)
    parser.add_argument("--first-seed", type=int, default=1000)
    parser.add_argument("--threads", type=int, default=None)
    parser.add_argument("--json", help="write every dataset's truth, cause, gain and timing")
    parser.add_argument("--effects", help="comma-separated: only these hidden effects (and 'none')")
    parser.add_argument(
        "--mismatch",
        action="store_true",
        help="the data come from a muscle that differs from its declared build (pamkit.synth.mismatch): "
        "the near-model world of a real rig",
    )
    arguments = parser.parse_args()

    names = ["none"] + hideable_effects()
    if arguments.effects:
        unknown = set(arguments.effects.split(",")) - set(names)
        if unknown:
            parser.error(f"--effects: unknown {', '.join(sorted(unknown))} (known: {', '.join(names)})")
        names = [n for n in names if n in arguments.effects.split(",")]
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for i in range(arguments.datasets):
            effect = names[i % len(names)]
            seed = arguments.first_seed + i
            folder = Path(scratch) / f"{i:04d}"
            # Its own stream: the protocol, build and noise stay the seed's with or without it.
            true_muscle = draw_mismatch(np.random.default_rng([seed, 7])) if arguments.mismatch else None
            files = synthesize(effect, seed, folder, true_muscle=true_muscle)
            manifest = json.loads(files.manifest.read_text())
            truth = manifest["effect"]
            experiment = load_experiment(files.experiment)
            started = time.perf_counter()
            simulate_experiment(experiment)
            one_simulation = time.perf_counter() - started
            started = time.perf_counter()
            try:
                d = diagnose(experiment, threads=arguments.threads)
            except Exception as error:  # a crash is a result of the sweep too: count it, go on
                print(f"ERROR seed {seed}: hidden {truth['name']}: {error!r}", file=sys.stderr, flush=True)
                rows.append(
                    {
                        "seed": seed,
                        "truth": truth["name"],
                        "options": truth.get("options", {}),
                        "parameters": truth.get("parameters", {}),
                        "cause": "error",
                        "gain": 0.0,
                        "seconds": time.perf_counter() - started,
                        "breakdown": {"baseline": 0.0, "candidates": 0.0},
                        "one_simulation_s": one_simulation,
                        "samples": int(experiment.time_s.size),
                        "largest_change": truth.get("largest_change", {}),
                        "verdict": repr(error),
                    }
                )
                continue
            seconds = time.perf_counter() - started
            report = to_json(d)
            best_gain = max(report["gain"].values()) if report["gain"] else 0.0
            rows.append(
                {
                    "seed": seed,
                    "truth": truth["name"],
                    "options": truth.get("options", {}),
                    "parameters": truth.get("parameters", {}),
                    "cause": report["cause"],
                    "gain": best_gain,
                    "seconds": seconds,
                    "breakdown": d.seconds,
                    "one_simulation_s": one_simulation,
                    "samples": int(experiment.time_s.size),
                    "largest_change": truth.get("largest_change", {}),
                    "verdict": report["verdict"],
                    "named": named_causes(report),
                    "mismatch": manifest.get("true_muscle", {}),
                    "noise": report["evidence"]["noise"],
                    "baseline_rmse": report["baseline"]["rmse"],
                    "extended_rmse": report["extended"]["rmse"],
                    "causes": report.get("causes", []),
                    "rejected": report["decision"].get("rejected"),
                }
            )
            mark = "ok " if rows[-1]["named"] == ([] if truth["name"] == "none" else [truth["name"]]) else "MISS"
            print(
                f"{mark} {i + 1:4d}/{arguments.datasets} seed {seed}: hidden {truth['name']:<24} named "
                f"{report['cause']:<24} {seconds:5.2f} s",
                file=sys.stderr,
                flush=True,
            )

    print_summary(rows, names)
    if arguments.json:
        Path(arguments.json).write_text(json.dumps(rows, indent=2) + "\n")
    return 0


def named_causes(report: dict) -> list[str]:
    """The causes a report names: its `causes` where it lists them, else its one `cause`."""
    if "causes" in report:
        return sorted({c["effect"].split(":")[0] for c in report["causes"]})
    cause = report["cause"].split(":")[0]
    return [] if cause in ("none", "unexplained", "error") else [cause]


def print_summary(rows: list[dict], names: list[str]) -> None:
    confusion = defaultdict(Counter)
    for row in rows:
        confusion[row["truth"]][row["cause"]] += 1
    causes = names + [extra for extra in ("unexplained", "error") if any(r["cause"] == extra for r in rows)]
    width = max(len(n) for n in names) + 1
    print(f"\nconfusion matrix ({len(rows)} datasets; rows: hidden effect, columns: named cause)\n")
    print(" " * width + " ".join(f"{k[:6]:>6}" for k in causes))
    for truth in names:
        print(f"{truth:<{width}}" + " ".join(f"{confusion[truth][c]:>6d}" for c in causes))
    effect_rows = [r for r in rows if r["truth"] != "none"]
    null_rows = [r for r in rows if r["truth"] == "none"]
    detected = sum(r["truth"] in r.get("named", []) for r in effect_rows)
    wrong = sum(any(n != r["truth"] for n in r.get("named", [])) for r in effect_rows)
    false_alarms = sum(bool(r.get("named")) for r in null_rows)
    unexplained_nulls = sum(r["cause"] == "unexplained" for r in null_rows)
    gains = [r["gain"] for r in effect_rows if r["cause"] == r["truth"]]
    seconds = np.array([r["seconds"] for r in rows])
    ratio = np.array([r["seconds"] / r["one_simulation_s"] for r in rows])
    baseline = np.array([r["breakdown"]["baseline"] for r in rows])
    candidates = np.array([r["breakdown"]["candidates"] for r in rows])
    print(
        f"\ndetection rate        {detected}/{len(effect_rows)} = {detected / max(len(effect_rows), 1):.3f}"
        f"  (wrong cause named: {wrong})"
    )
    print(
        f"false-alarm rate      {false_alarms}/{len(null_rows)} = {false_alarms / max(len(null_rows), 1):.3f}"
        f"  (nulls called unexplained: {unexplained_nulls})"
    )
    median_gain = np.median(gains) if gains else float("nan")
    print(f"median held-out gain  {median_gain:.3f} (correctly named causes, best channel)")
    print(
        f"time per diagnosis    median {np.median(seconds):.2f} s, 90th percentile {np.percentile(seconds, 90):.2f} s, "
        f"max {seconds.max():.2f} s"
    )
    print(f"                      = median {np.median(ratio):.0f} x one simulation of the same dataset")
    print(
        f"breakdown (median)    baseline calibration {np.median(baseline):.2f} s, candidate fits "
        f"{np.median(candidates):.2f} s"
    )
    print_by_visibility(effect_rows)
    ratios = [
        {c: r["baseline_rmse"][c] / r["noise"][c] for c in r.get("noise", {}) if r["noise"][c] > 0} for r in null_rows
    ]
    if any(ratios):
        for channel in ("force_N", "gauge_pressure_Pa"):
            values = [x[channel] for x in ratios if channel in x]
            if values:
                print(f"nulls' baseline {channel} RMSE / noise: median {np.median(values):.2f}, max {max(values):.2f}")
    misses = [r for r in rows if r["cause"] != r["truth"]]
    if misses:
        print("\nmisses:")
        for r in misses:
            change = {k: round(v, 2) for k, v in r.get("largest_change", {}).items()}
            print(
                f"  seed {r['seed']}: hidden {r['truth']} {r['options']} "
                f"{ {k: round(v, 4) for k, v in r['parameters'].items()} } (largest change {change}) -> "
                f"{r['cause']}: {r['verdict'][:140]}"
            )


def visibility(row: dict) -> float:
    """How plainly a hidden effect shows: the largest change it makes to a measured channel over
    that channel's noise (the report's estimate)."""
    noise = row.get("noise", {})
    return max((row["largest_change"].get(c, 0.0) / noise[c] for c in noise if noise[c] > 0), default=0.0)


def print_by_visibility(effect_rows: list[dict]) -> None:
    """Named right and wrong in thirds of the hidden effects' visibility, weakest first."""
    if not effect_rows or "noise" not in effect_rows[0]:
        return
    ordered = sorted(effect_rows, key=visibility)
    print("\nby visibility (largest change / noise), thirds from the weakest:")
    for third in np.array_split(np.arange(len(ordered)), 3):
        part = [ordered[i] for i in third]
        if not part:
            continue
        right = sum(r["truth"] in r.get("named", []) for r in part)
        wrong = sum(any(n != r["truth"] for n in r.get("named", [])) for r in part)
        span = f"{visibility(part[0]):7.1f}-{visibility(part[-1]):<7.1f}"
        print(f"  {span} right {right:3d}/{len(part):<3d} wrong {wrong:3d}")


if __name__ == "__main__":
    sys.exit(main())
