"""Diagnosis on families of tests made outside pamkit (docs/validation.md, "Data pamkit did not make").

    PYTHONPATH=build/python python3 bench/bench_families.py [--per-family 3] [--families a,b]
        [--jobs 1] [--first-seed 1] [--json OUT.json] [--timeout 900]

Every dataset is written by tests/independent (an independent model of a braided muscle and the
bench's instruments; it never imports pamkit) and handed to ``python -m pamkit diagnose`` through
files only, as a user would. Per family, the verdicts are counted as

- right: the hidden catalog effect is the cause;
- honest: ``none`` or ``unexplained`` (for a catalog family this is a miss, counted here too);
- wrong: any other catalog name (listed; "truth_only_as_partner" in the JSON counts those whose
  extended model pairs the wrong cause with the true effect);
- none+structure: ``none`` while some channel's held-out baseline RMSE exceeds 1.5x its noise
  (the factor of rule 5 of docs/diagnosis.md; ``baseline.rmse`` against ``evidence.noise``; a
  table's report states what it leaves above the noise, ``remainder.channels``);
- error: a non-zero exit or a timeout, with the last line of stderr.

The median decision margin (the smallest of the report's ``decision.margins``) is printed, and the median held-out
RMSE of the calibrated baseline over the noise for force (F/σ) and pressure (p/σ); then the seconds per
diagnosis for each kind of test (sealed cyclic, supplied sweep, table: median, 90th percentile, slowest).
Datasets are generated into a temporary directory and deleted.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import tomllib

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from independent.families import FAMILIES

HONEST_CAUSES = ("none", "unexplained")


def diagnose(toml: Path, timeout_s: float, threads: int) -> dict:
    """Runs the command line on one experiment; the report, or the error."""
    report_path = toml.with_name("report.json")
    started = time.perf_counter()
    try:
        done = subprocess.run(
            [
                sys.executable,
                "-m",
                "pamkit",
                "diagnose",
                str(toml),
                "--json",
                str(report_path),
                "--quiet",
                "--threads",
                str(threads),
            ],
            check=False,
            capture_output=True,
            text=True,
            timeout=timeout_s,
        )
    except subprocess.TimeoutExpired:
        return {"error": f"timeout after {timeout_s:.0f} s", "seconds": time.perf_counter() - started}
    seconds = time.perf_counter() - started
    if done.returncode != 0:
        lines = [line for line in done.stderr.strip().splitlines() if line.strip()]
        message = lines[-1].replace(str(toml.parent), "DATASET") if lines else f"exit {done.returncode}"
        return {"error": message, "seconds": seconds}
    return {"report": json.loads(report_path.read_text()), "seconds": seconds}


def margin_of(report: dict):
    """The decision's margin (docs/reference/report.md, "Margin"): the smallest of the report's
    `decision.margins`, each a distance from its threshold (> 0: the decision holds)."""
    margins = report.get("decision", {}).get("margins", {}) if isinstance(report.get("decision"), dict) else {}
    values = [float(v) for v in margins.values() if isinstance(v, (int, float))]
    return min(values) if values else None


def candidate_gains(report: dict) -> list[dict]:
    """Every candidate a report fitted, with its combined held-out gain (`score`) and its gain on
    each channel: what a cause that was not named reached, so that a bench can say how far the
    causes that are not in the data get (the gains a rule must stay above)."""
    return [
        {"effect": c.get("effect"), "score": c.get("score"), "gain": c.get("gain"), "credible": c.get("credible")}
        for c in report.get("candidates", []) or []
        if isinstance(c, dict)
    ]


def noise_of(report: dict) -> dict:
    """Each channel's noise as the report states it: a time series' under `evidence`, a table's at
    the top."""
    return report["evidence"]["noise"] if "evidence" in report else report["noise"]


def structure_left(report: dict) -> dict:
    """Channels whose held-out baseline RMSE exceeds the report's stated factor of their noise
    (rule 5 of docs/diagnosis.md; `evidence.none_within_noise`): ratio. A table's report states
    what is left above that factor itself (`remainder.channels`)."""
    if "evidence" not in report:
        return dict((report.get("remainder") or {}).get("channels", {}))
    rmse, noise = report["baseline"]["rmse"], report["evidence"]["noise"]
    factor = report["evidence"]["none_within_noise"]
    return {c: rmse[c] / noise[c] for c in rmse if c in noise and noise[c] > 0 and rmse[c] > factor * noise[c]}


def worst_test(report: dict) -> dict:
    """A campaign's test whose baseline is furthest above its noise (its own report), else the
    report itself: what the rows below read the held-out errors from."""
    if report.get("kind") != "campaign":
        return report
    return max(
        report["per_test"],
        key=lambda test: max(
            r / noise_of(test)[c] for c, r in test["baseline"]["rmse"].items() if noise_of(test)[c] > 0
        ),
    )


def classify(expected: str, outcome: dict, present: tuple[str, ...] = ()) -> dict:
    if "error" in outcome:
        return {"outcome": "error", "cause": None, "message": outcome["error"]}
    report = outcome["report"]
    cause = report["cause"]
    errors = worst_test(report)
    rmse, noise = errors["baseline"]["rmse"], noise_of(errors)
    extended = (errors.get("extended") or {}).get("rmse", {})
    # Every cause a report names (its `causes` where it lists them), by effect name.
    named = (
        [c["effect"].split(":")[0] for c in report["causes"]]
        if "causes" in report
        else ([] if cause in HONEST_CAUSES else [cause.split(":")[0]])
    )
    row = {
        "cause": cause,
        "named": named,
        "effects": (report.get("extended") or {}).get("effects", []),
        "margin": margin_of(report),
        "verdict": report.get("verdict", ""),
        "baseline_rmse_over_noise": {c: rmse[c] / noise[c] for c in rmse if noise.get(c, 0) > 0},
        "extended_rmse_over_noise": {c: extended[c] / noise[c] for c in extended if noise.get(c, 0) > 0},
        "causes": report.get("causes", []),
        "candidates": candidate_gains(report),
    }
    wrong = [n for n in named if n != expected and n not in present]
    if wrong:
        row["outcome"] = "wrong"
        row["cause"] = wrong[0]  # the wrong name is what the table lists
    elif expected in named or any(n in present for n in named):
        row["outcome"] = "right"
    else:
        row["outcome"] = "honest"
        if cause == "none":
            row["structure"] = structure_left(errors)
    return row


def kind_of(toml: Path) -> str:
    """What kind of test a dataset is, as its file declares it: a time series by its gas (sealed
    cyclic, supplied sweep), a table by its kind, or a campaign of tests."""
    declared = tomllib.loads(toml.read_text())
    if "campaign" in declared:
        return "campaign"
    test = declared.get("test", {})
    kind = test.get("kind", "series")
    return f"{kind} ({test.get('gas', 'sealed')})" if kind == "series" else kind


def timing_by_kind(rows: list[dict]) -> dict:
    """Seconds per diagnosis for each kind of test: median, 90th percentile and slowest."""
    out = {}
    for kind in sorted({r["kind"] for r in rows}):
        seconds = sorted(r["seconds"] for r in rows if r["kind"] == kind)
        out[kind] = {
            "datasets": len(seconds),
            "median_seconds": statistics.median(seconds),
            "p90_seconds": seconds[min(len(seconds) - 1, int(0.9 * len(seconds)))],
            "slowest_seconds": seconds[-1],
        }
    return out


def summarise(rows: list[dict]) -> dict:
    counts = Counter(r["outcome"] for r in rows)
    margins = [r["margin"] for r in rows if r.get("margin") is not None]
    return {
        "expected": rows[0]["expected"],
        "datasets": len(rows),
        "right": counts["right"],
        "honest": counts["honest"],
        "wrong": counts["wrong"],
        "wrong_names": dict(Counter(r["cause"] for r in rows if r["outcome"] == "wrong")),
        "truth_only_as_partner": sum(
            1 for r in rows if r["outcome"] == "wrong" and r["expected"] in r.get("effects", [])
        ),
        "none_with_structure": sum(1 for r in rows if r.get("cause") == "none" and r.get("structure")),
        "errors": counts["error"],
        "error_messages": sorted({r["message"] for r in rows if r["outcome"] == "error"}),
        "median_margin": statistics.median(margins) if margins else None,
        "median_seconds": statistics.median(r["seconds"] for r in rows),
        "median_baseline_rmse_over_noise": {
            c: statistics.median(
                r["baseline_rmse_over_noise"][c] for r in rows if c in r.get("baseline_rmse_over_noise", {})
            )
            for c in sorted({c for r in rows for c in r.get("baseline_rmse_over_noise", {})})
        },
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--per-family", type=int, default=3)
    parser.add_argument("--families", help=f"comma-separated, of: {', '.join(FAMILIES)}")
    parser.add_argument("--first-seed", type=int, default=1)
    parser.add_argument("--jobs", type=int, default=1, help="diagnoses at once (default 1: CPU is scarce)")
    parser.add_argument("--threads", type=int, default=1, help="--threads of each diagnosis")
    parser.add_argument("--timeout", type=float, default=900.0, help="seconds per diagnosis")
    parser.add_argument("--json", help="write every dataset's row and the table")
    arguments = parser.parse_args()
    names = arguments.families.split(",") if arguments.families else list(FAMILIES)
    unknown = [n for n in names if n not in FAMILIES]
    if unknown:
        parser.error(
            f"unknown famil{'y' if len(unknown) == 1 else 'ies'} {', '.join(unknown)}; known: {', '.join(FAMILIES)}"
        )

    with tempfile.TemporaryDirectory() as scratch:
        work = []
        for name in names:
            for seed in range(arguments.first_seed, arguments.first_seed + arguments.per_family):
                dataset = FAMILIES[name](seed, Path(scratch) / f"{name}-{seed}")
                work.append((name, seed, dataset))

        def run(item):
            name, seed, dataset = item
            outcome = diagnose(dataset.experiment, arguments.timeout, arguments.threads)
            row = {
                "family": name,
                "seed": seed,
                "expected": dataset.expected,
                "truth": dataset.truth,
                "kind": kind_of(dataset.experiment),
                "seconds": outcome["seconds"],
                **classify(dataset.expected, outcome, dataset.present),
            }
            extra = f" ({row['message']})" if row["outcome"] == "error" else ""
            print(
                f"{name:28s} seed {seed:3d}: {row['outcome']:6s} cause {row['cause']}{extra} [{row['seconds']:.1f} s]",
                file=sys.stderr,
                flush=True,
            )
            return row

        with ThreadPoolExecutor(max_workers=max(1, arguments.jobs)) as pool:
            rows = list(pool.map(run, work))

    table = {name: summarise([r for r in rows if r["family"] == name]) for name in names}
    header = (
        f"{'family':28s} {'expected':14s} {'n':>2s} {'right':>5s} {'honest':>6s} {'wrong':>5s} {'none+str':>8s} "
        f"{'err':>3s} {'margin':>6s} {'s':>5s} {'F/σ':>5s} {'p/σ':>5s}  wrong names / errors"
    )
    print(header)
    print("-" * len(header))
    for name, s in table.items():
        margin = "-" if s["median_margin"] is None else f"{s['median_margin']:.3f}"
        notes = ", ".join(f"{k}×{v}" for k, v in s["wrong_names"].items())
        ratio = s["median_baseline_rmse_over_noise"]
        force, pressure = (f"{ratio[c]:5.1f}" if c in ratio else "    -" for c in ("force_N", "gauge_pressure_Pa"))
        if s["error_messages"]:
            notes += ("; " if notes else "") + " | ".join(m[:120] for m in s["error_messages"])
        print(
            f"{name:28s} {s['expected']:14s} {s['datasets']:2d} {s['right']:5d} {s['honest']:6d} {s['wrong']:5d} "
            f"{s['none_with_structure']:8d} {s['errors']:3d} {margin:>6s} "
            f"{s['median_seconds']:5.1f} {force} {pressure}  {notes}"
        )
    total = Counter()
    for s in table.values():
        total.update({k: s[k] for k in ("datasets", "right", "honest", "wrong", "none_with_structure", "errors")})
    print(
        f"{'all':28s} {'':14s} {total['datasets']:2d} {total['right']:5d} {total['honest']:6d} {total['wrong']:5d} "
        f"{total['none_with_structure']:8d} {total['errors']:3d}"
    )
    timing = timing_by_kind(rows)
    print(f"\n{'kind':22s} {'n':>3s} {'median s':>8s} {'p90 s':>6s} {'slowest s':>9s}")
    for kind, t in timing.items():
        print(
            f"{kind:22s} {t['datasets']:3d} {t['median_seconds']:8.1f} {t['p90_seconds']:6.1f} "
            f"{t['slowest_seconds']:9.1f}"
        )
    if arguments.json:
        Path(arguments.json).write_text(
            json.dumps({"table": table, "total": dict(total), "timing": timing, "rows": rows}, indent=2, default=float)
            + "\n"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
