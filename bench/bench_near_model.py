"""Diagnosis in the near-model world: data from the thesis's own model, made to differ from it as
real muscles do, with a catalog cause hidden at three strengths, and nulls.

    PYTHONPATH=build/python python3 bench/bench_near_model.py [--seeds 3] [--first-seed 1]
        [--nulls 5] [--families a,b] [--strengths weak,medium,strong] [--jobs 1] [--threads 1]
        [--json OUT.json] [--timeout 900] [--quick]

Every dataset is written by tests/independent/near_families.py (never importing pamkit) and
handed to ``python -m pamkit diagnose FILE --json REPORT --quiet`` through files only. The causes
a report names are, if it has a key ``causes`` (a list of objects each with an ``"effect"``),
those effects; otherwise its ``cause`` unless that is ``none`` or ``unexplained``. A dataset is

- right: every hidden cause is named and nothing else (beside physics the dataset shows that its
  generator has built in, e.g. a braid going slack: named, it is not wrong);
- wrong: some named cause is neither hidden nor shown;
- partial: some but not all of two hidden causes named, nothing wrong;
- honest: nothing named (``none``, or ``unexplained`` / a remainder only). For a null this is the
  right answer; for a hidden cause it is a miss.

Printed: the confusion matrix (rows: the family, which says what is hidden; columns: what was
named; a report naming two causes counts in both columns), right / wrong / partial / honest per
family and per strength (``chan``: right by name but on another channel than the hidden one, e.g. a
lag named on the force for a lagging pressure), the median decision margin (the smallest of
``decision.margins``), the median held-out gain pamkit's fit of the hidden cause reached (its
candidate's ``score``, named or not; the smaller of two), the upper strengths' rate again over the
datasets where that gain reaches what a cause needs (``VISIBLE_GAIN``: below it the data do not
show the cause to pamkit's model at all), the median calibrated baseline's held-out
RMSE over the noise for force and pressure (F/σ, p/σ), the nulls' verdicts and the distribution of
their F/σ and p/σ, the reasons given for the misses and the wrong names (``decision.rejected``'s
first reason, or the verdict's words, numbers blanked so that alike reasons count together), and
the seconds per diagnosis, wall and CPU (user + system of the diagnosing process: on a shared
machine the wall time says how busy the others were). ``--quick``: the fixed subset
near_families.QUICK (every family once at medium strength, four nulls), a fast loop. Datasets are
written into a temporary directory and deleted.

``--glitches N`` throws N glitches into each measured channel of every dataset's file before it is
diagnosed, as a real rig's line noise would: samples drawn among all but the first and last ten,
each moved 30-100 times the channel's noise (the median second difference's, a robust scale no
ramp moves) up or down. ``--keep-glitches`` declares them kept (``[test] glitches = "keep"``):
the diagnosis as it was before it searched for them. Compared with the clean world's JSON
(bench/decision_diff.py), the decisions the glitches change.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
import zlib
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from bench_families import candidate_gains, margin_of  # read as bench_families reads them
from independent.near_families import FAMILIES, QUICK, STRENGTHS

from pamkit.diagnosis.significance import MIN_GAIN
from pamkit.io.columns import si_name  # the truth names a file's column, the report pamkit's

HONEST_CAUSES = ("none", "unexplained")
# What a cause must gain: a hidden cause whose own fit gains less is not shown by the data to
# pamkit's model, whatever the rules.
VISIBLE_GAIN = MIN_GAIN


GLITCHED_COLUMNS = ("force_N", "pressure_kPa", "temperature_C")
GLITCH_SIZES = (30.0, 100.0)  # times the channel's noise


def throw_glitches(toml: Path, count: int, seed: list[int], keep: bool) -> None:
    """Moves `count` samples of each measured channel of the test's CSV off by GLITCH_SIZES times
    its noise (the module docstring); with `keep`, declares them kept in its [test]."""
    text = toml.read_text()
    data = toml.parent / re.search(r'^data\s*=\s*"([^"]+)"', text, re.M).group(1)
    lines = data.read_text().splitlines()
    header = lines[0].split(",")
    table = np.array([[float(cell) for cell in line.split(",")] for line in lines[1:]])
    rng = np.random.default_rng(seed)
    for column in (header.index(name) for name in GLITCHED_COLUMNS if name in header):
        noise = 1.4826 * float(np.median(np.abs(np.diff(table[:, column], 2)))) / math.sqrt(6.0)
        rows = rng.choice(np.arange(10, len(table) - 10), count, replace=False)
        table[rows, column] += rng.choice([-1.0, 1.0], count) * rng.uniform(*GLITCH_SIZES, count) * max(noise, 1e-9)
    data.write_text(",".join(header) + "\n" + "".join(",".join(f"{v:.10g}" for v in row) + "\n" for row in table))
    if keep:
        toml.write_text(text.replace("[test]\n", '[test]\nglitches = "keep"\n', 1))


def diagnose(toml: Path, timeout_s: float, threads: int) -> dict:
    """`python -m pamkit diagnose TOML --json REPORT --quiet`: the report (or the error), its wall
    seconds and the CPU seconds the process used (user + system, its threads included), which on
    a shared machine say what the diagnosis costs when its wall time says how busy the others were."""
    report_path = toml.with_name("report.json")
    command = [sys.executable, "-m", "pamkit", "diagnose", str(toml), "--json", str(report_path), "--quiet"]
    started = time.perf_counter()
    with open(toml.with_name("stderr.txt"), "w+") as stderr:
        process = subprocess.Popen(command + ["--threads", str(threads)], stdout=subprocess.DEVNULL, stderr=stderr)
        while True:
            pid, status, usage = os.wait4(process.pid, os.WNOHANG)
            if pid:
                break
            if time.perf_counter() - started > timeout_s:
                process.kill()
                os.wait4(process.pid, 0)
                return {"error": f"timeout after {timeout_s:.0f} s", "seconds": timeout_s, "cpu_seconds": None}
            time.sleep(0.05)
        seconds, cpu = time.perf_counter() - started, usage.ru_utime + usage.ru_stime
        process.returncode = os.waitstatus_to_exitcode(status)
        if process.returncode != 0:
            stderr.seek(0)
            lines = [line for line in stderr.read().strip().splitlines() if line.strip()]
            message = lines[-1].replace(str(toml.parent), "DATASET") if lines else f"exit {process.returncode}"
            return {"error": message, "seconds": seconds, "cpu_seconds": cpu}
    return {"report": json.loads(report_path.read_text()), "seconds": seconds, "cpu_seconds": cpu}


def named_causes(report: dict) -> dict[str, str | None]:
    """The catalog causes a report names, each with the channel it acts on (None for an effect
    without one): its `causes` list's effects when it has one, else its single `cause` unless that
    says nothing was found."""
    if isinstance(report.get("causes"), list):
        return {
            c["effect"].split(":")[0]: (c.get("params") or {}).get("channel") or c.get("channel")
            for c in report["causes"]
            if isinstance(c, dict) and "effect" in c
        }
    cause = report.get("cause")
    if cause in HONEST_CAUSES or cause is None:
        return {}
    extended = report.get("extended") if isinstance(report.get("extended"), dict) else {}
    return {cause.split(":")[0]: (extended.get("params") or {}).get("channel")}


def outcome_of(hidden: tuple[str, ...], present: tuple[str, ...], named) -> str:
    """right / wrong / partial / honest (module docstring)."""
    named = set(named)
    if named - set(hidden) - set(present):
        return "wrong"
    found = named & set(hidden)
    if hidden and found == set(hidden):
        return "right"
    return "partial" if found else "honest"


def candidate_name(effect: str) -> tuple[str, str | None]:
    """("sensor_lag", "pressure_kPa") from a candidate's "sensor_lag:channel=pressure_kPa"."""
    name, _, rest = effect.partition(":")
    options = dict(part.split("=", 1) for part in rest.split(",") if "=" in part)
    return name, options.get("channel")


def hidden_gain(report: dict, channels: dict[str, str | None]):
    """The held-out gain (combined score) pamkit's fit of each hidden cause reached, on its channel,
    named or not; for two hidden causes the smaller."""
    scores = {}
    for candidate in report.get("candidates", []) or []:
        name, channel = candidate_name(str(candidate.get("effect", "")))
        wanted = channels.get(name, "absent")
        if wanted != "absent" and (wanted is None or wanted == channel):
            if isinstance(candidate.get("score"), (int, float)):
                scores[name] = max(scores.get(name, -math.inf), float(candidate["score"]))
    return min(scores.values()) if channels and len(scores) == len(channels) else None


NUMBER = re.compile(r"[-+]?\d+(\.\d+)?(e[-+]?\d+)?")


def why_missed(report: dict) -> str:
    """What stood in the way, numbers blanked so that alike reasons count together: the rejected
    best fit's first reason, or else the verdict's own words."""
    decision = report.get("decision") if isinstance(report.get("decision"), dict) else {}
    rejected = decision.get("rejected")
    if isinstance(rejected, dict) and rejected.get("because"):
        because = rejected["because"]
        text = f"{rejected.get('effect', '?')} rejected: {because[0] if isinstance(because, list) else because}"
    else:
        verdict = str(report.get("verdict", ""))
        text = verdict.split(" (held-out RMSE")[0] + (
            ": " + verdict.split("best candidate ", 1)[1].split(";")[0] if "best candidate " in verdict else ""
        )
    return NUMBER.sub("#", text)[:150]


def classify(dataset, outcome: dict) -> dict:
    if "error" in outcome:
        return {"outcome": "error", "named": [], "message": outcome["error"]}
    report = outcome["report"]
    named = named_causes(report)
    declared = {c: (dataset.truth.get("cause", {}).get(c) or {}).get("channel") for c in dataset.hidden}
    channels = {c: si_name(channel) if channel else None for c, channel in declared.items()}
    rmse, noise = report["baseline"]["rmse"], report["evidence"]["noise"]
    row = {
        "cause": report.get("cause"),
        "named": sorted(named),
        "named_channels": named,
        "outcome": outcome_of(dataset.hidden, dataset.present, named),
        # a hidden channel effect named on another channel: right by name, wrong by mechanism
        "other_channel": any(channels.get(c) and named[c] and named[c] != channels[c] for c in named if c in channels),
        "margin": margin_of(report),
        "hidden_gain": hidden_gain(report, channels),
        "baseline_rmse_over_noise": {c: rmse[c] / noise[c] for c in rmse if noise.get(c, 0) > 0},
        "verdict": report.get("verdict", ""),
        "causes": report.get("causes", []),
        "candidates": candidate_gains(report),
    }
    if row["outcome"] != "right" and (dataset.hidden or row["outcome"] == "wrong"):
        row["why"] = why_missed(report)
    return row


def median(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def quantiles(values):
    values = sorted(v for v in values if v is not None)
    if not values:
        return None
    pick = lambda q: values[min(len(values) - 1, int(q * (len(values) - 1) + 0.5))]  # noqa: E731
    return {"min": values[0], "q25": pick(0.25), "median": pick(0.5), "q75": pick(0.75), "max": values[-1]}


def summarise(rows: list[dict]) -> dict:
    counts = Counter(r["outcome"] for r in rows)
    ratio = lambda c: median(r["baseline_rmse_over_noise"].get(c) for r in rows if "baseline_rmse_over_noise" in r)  # noqa: E731
    return {
        "datasets": len(rows),
        **{k: counts[k] for k in ("right", "wrong", "partial", "honest", "error")},
        "right_on_another_channel": sum(1 for r in rows if r["outcome"] == "right" and r.get("other_channel")),
        "median_margin": median(r.get("margin") for r in rows),
        "median_hidden_gain": median(r.get("hidden_gain") for r in rows),
        "median_force_over_noise": ratio("force_N"),
        "median_pressure_over_noise": ratio("pressure_kPa"),
        "median_seconds": median(r["seconds"] for r in rows),
        "median_cpu_seconds": median(r["cpu_seconds"] for r in rows),
    }


def work_list(arguments) -> list[tuple[str, int, str | None]]:
    if arguments.quick:
        return list(QUICK)
    names = arguments.families.split(",") if arguments.families else list(FAMILIES)
    unknown = [n for n in names if n not in FAMILIES]
    if unknown:
        raise SystemExit(
            f"unknown famil{'y' if len(unknown) == 1 else 'ies'} {', '.join(unknown)}; known: {', '.join(FAMILIES)}"
        )
    strengths = arguments.strengths.split(",") if arguments.strengths else list(STRENGTHS)
    bad = [s for s in strengths if s not in STRENGTHS]
    if bad:
        raise SystemExit(f"unknown strength {', '.join(bad)}; known: {', '.join(STRENGTHS)}")
    seeds = range(arguments.first_seed, arguments.first_seed + arguments.seeds)
    null_seeds = range(arguments.first_seed, arguments.first_seed + arguments.nulls)
    items = []
    for name in names:
        if FAMILIES[name].hidden:
            items += [(name, seed, strength) for strength in strengths for seed in seeds]
        else:
            items += [(name, seed, None) for seed in null_seeds]
    return items


def print_confusion(rows: list[dict]) -> dict:
    labels = list(dict.fromkeys(r["family"] for r in rows))
    columns = sorted({c for r in rows for c in r.get("named", [])})
    columns += ["none", "unexplained", "error"]
    matrix = {label: Counter() for label in labels}
    for r in rows:
        label = r["family"]
        if r["outcome"] == "error":
            matrix[label]["error"] += 1
        elif r["named"]:
            for c in r["named"]:
                matrix[label][c] += 1
        else:
            matrix[label][r["cause"] if r["cause"] in HONEST_CAUSES else "unexplained"] += 1
    width = max(len(label) for label in labels) + 1
    print("Confusion matrix (rows: family, hidden; columns: named)")
    print(" " * width + " ".join(f"{c[:6]:>6s}" for c in columns))
    for label in labels:
        print(f"{label:{width}s}" + " ".join(f"{matrix[label][c]:6d}" for c in columns))
    print("columns: " + ", ".join(columns))
    return {label: dict(matrix[label]) for label in labels}


def named_gains(rows: list[dict]) -> dict[str, dict[str, list[float]]]:
    """Each cause named, right (in the data) and wrong, with the gain each naming had on the
    channels the cause acts on (`gain_own_channels`: alone against the calibrated baseline, or as
    a second cause beside the first): how far a rule's threshold sits from both."""
    out: dict[str, dict[str, list[float]]] = {}
    for r in rows:
        truth = set(r.get("hidden", [])) | set(r.get("present", []))
        for cause in r.get("causes") or []:
            name, gain = str(cause.get("effect", "")).split(":")[0], cause.get("gain_own_channels")
            if isinstance(gain, (int, float)):
                out.setdefault(name, {"right": [], "wrong": []})["right" if name in truth else "wrong"].append(gain)
    return out


def print_named_gains(gains: dict[str, dict[str, list[float]]]) -> None:
    def span(values):
        return f"{len(values):3d} {min(values):6.3f}-{max(values):5.3f}" if values else f"{0:3d} {'':12s}"

    print("\neach cause named, in the data (right) and not (wrong): count, gain on its own channels")
    for name, sides in sorted(gains.items()):
        print(f"  {name:26s} right {span(sorted(sides['right']))}   wrong {span(sorted(sides['wrong']))}")


def fmt(value, spec):
    return "-" if value is None else format(value, spec)


def print_table(title: str, groups: dict[str, list[dict]]) -> dict:
    table = {key: summarise(rows) for key, rows in groups.items()}
    width = max([len(title)] + [len(k) for k in table]) + 1
    header = (
        f"{title:{width}s} {'n':>3s} {'right':>5s} {'chan':>4s} {'wrong':>5s} {'part':>4s} {'honest':>6s} {'err':>3s} "
        f"{'margin':>7s} {'gain':>5s} {'F/σ':>5s} {'p/σ':>5s} {'s':>5s}"
    )
    print(header)
    print("-" * len(header))
    for key, s in table.items():
        print(
            f"{key:{width}s} {s['datasets']:3d} {s['right']:5d} {s['right_on_another_channel']:4d} {s['wrong']:5d} "
            f"{s['partial']:4d} {s['honest']:6d} "
            f"{s['error']:3d} {fmt(s['median_margin'], '7.3f'):>7s} {fmt(s['median_hidden_gain'], '5.2f'):>5s} "
            f"{fmt(s['median_force_over_noise'], '5.1f'):>5s} {fmt(s['median_pressure_over_noise'], '5.1f'):>5s} "
            f"{fmt(s['median_seconds'], '5.1f'):>5s}"
        )
    return table


def print_grid(rows: list[dict]) -> dict:
    """right / wrong / honest (partial and errors after a +) per family and strength."""
    families = list(dict.fromkeys(r["family"] for r in rows if r["hidden"]))
    strengths = [s for s in STRENGTHS if any(r["strength"] == s for r in rows)]
    grid = {}
    width = max([6] + [len(f) for f in families]) + 1
    print(f"{'right/wrong/honest':{width}s}" + "".join(f"{s:>12s}" for s in strengths))
    for family in families:
        cells = []
        for strength in strengths:
            counts = Counter(r["outcome"] for r in rows if r["family"] == family and r["strength"] == strength)
            grid.setdefault(family, {})[strength] = dict(counts)
            extra = counts["partial"] + counts["error"]
            cells.append(f"{counts['right']}/{counts['wrong']}/{counts['honest']}" + (f"+{extra}" if extra else ""))
        print(f"{family:{width}s}" + "".join(f"{c:>12s}" for c in cells))
    return grid


def add_world_arguments(parser: argparse.ArgumentParser) -> None:
    """Which of the near-model world's datasets (work_list reads them) and how they are diagnosed."""
    parser.add_argument("--seeds", type=int, default=3, help="seeds per family and strength")
    parser.add_argument("--first-seed", type=int, default=1)
    parser.add_argument("--nulls", type=int, default=5, help="seeds per null family (two: sealed, supplied)")
    parser.add_argument("--families", help=f"comma-separated, of: {', '.join(FAMILIES)}")
    parser.add_argument("--strengths", help=f"comma-separated, of: {', '.join(STRENGTHS)}")
    parser.add_argument("--jobs", type=int, default=1, help="diagnoses at once (default 1: CPU is scarce)")
    parser.add_argument("--threads", type=int, default=1, help="--threads of each diagnosis")
    parser.add_argument("--timeout", type=float, default=900.0, help="seconds per diagnosis")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_world_arguments(parser)
    parser.add_argument("--quick", action="store_true", help="the fixed fast subset (near_families.QUICK)")
    parser.add_argument("--json", help="write every dataset's row and the tables")
    parser.add_argument("--glitches", type=int, default=0, help="glitches thrown into each measured channel")
    parser.add_argument("--keep-glitches", action="store_true", help='declare them kept ([test] glitches = "keep")')
    arguments = parser.parse_args()
    items = work_list(arguments)
    started = time.perf_counter()

    with tempfile.TemporaryDirectory() as scratch:

        def run(item):
            name, seed, strength = item
            started = time.perf_counter()
            dataset = FAMILIES[name].make(seed, Path(scratch) / f"{name}-{strength}-{seed}", strength)
            if arguments.glitches:
                throw_glitches(
                    dataset.experiment, arguments.glitches, [seed, zlib.crc32(name.encode())], arguments.keep_glitches
                )
            generated = time.perf_counter() - started
            outcome = diagnose(dataset.experiment, arguments.timeout, arguments.threads)
            row = {
                "family": name,
                "seed": seed,
                "strength": strength,
                "hidden": list(dataset.hidden),
                "present": list(dataset.present),
                "truth": dataset.truth,
                "generate_seconds": generated,
                "seconds": outcome["seconds"],
                "cpu_seconds": outcome["cpu_seconds"],
                **classify(dataset, outcome),
            }
            print(
                f"{name:30s} {strength or 'null':6s} seed {seed:3d}: {row['outcome']:7s} "
                f"named {row['named'] or row.get('cause')} [{row['seconds']:.1f} s]"
                + (f" ({row['message']})" if row["outcome"] == "error" else ""),
                file=sys.stderr,
                flush=True,
            )
            return row

        with ThreadPoolExecutor(max_workers=max(1, arguments.jobs)) as pool:
            rows = list(pool.map(run, items))

    confusion = print_confusion(rows)
    print()
    by_family = print_table(
        "family", {n: [r for r in rows if r["family"] == n] for n in dict.fromkeys(r["family"] for r in rows)}
    )
    print()
    caused = [r for r in rows if r["hidden"]]
    strengths = [s for s in STRENGTHS if any(r["strength"] == s for r in caused)]
    by_strength = print_table("strength", {s: [r for r in caused if r["strength"] == s] for s in strengths})
    print()
    grid = print_grid(caused)
    upper = [r for r in caused if r["strength"] in ("medium", "strong")]
    total = Counter(r["outcome"] for r in rows)
    nulls = [r for r in rows if not r["hidden"]]
    print(
        f"\nupper two strengths: {sum(r['outcome'] == 'right' for r in upper)}/{len(upper)} right, "
        f"{sum(r['outcome'] == 'wrong' for r in upper)} wrong; overall wrong {total['wrong']}/{len(rows)}"
    )
    # What no rule could name honestly: the hidden cause's own fit gains less than a cause must
    # (MIN_GAIN), its effect absorbed by the calibrated build (a supplied transducer's offset and
    # gain at one held length are a braid wound otherwise and a membrane's scale).
    visible = [r for r in upper if (r.get("hidden_gain") or 0.0) >= VISIBLE_GAIN]
    print(
        f"  of which the hidden cause's own fit gains at least {VISIBLE_GAIN} (what a cause must): "
        f"{sum(r['outcome'] == 'right' for r in visible)}/{len(visible)} right, "
        f"{sum(r['outcome'] == 'wrong' for r in visible)} wrong"
    )
    null_verdicts = Counter(
        "error"
        if r["outcome"] == "error"
        else ("wrong: " + ",".join(r["named"]))
        if r["outcome"] == "wrong"
        else r["cause"]
        for r in nulls
    )
    force = quantiles([r.get("baseline_rmse_over_noise", {}).get("force_N") for r in nulls])
    pressure = quantiles([r.get("baseline_rmse_over_noise", {}).get("pressure_kPa") for r in nulls])
    if nulls:
        print(f"nulls ({len(nulls)}): " + ", ".join(f"{k} {v}" for k, v in sorted(null_verdicts.items())))
    for label, q in (("F/σ", force), ("p/σ", pressure)):
        if q:
            print(f"  nulls' baseline {label}: " + ", ".join(f"{k} {v:.2f}" for k, v in q.items()))
    misses = Counter(r["why"] for r in caused if r.get("why"))
    if misses:
        print("\nwhy the hidden cause was not named, or what was named instead (count; numbers as #):")
        for why, count in misses.most_common(15):
            print(f"  {count:3d}  {why}")
    gains = named_gains(rows)
    print_named_gains(gains)
    seconds = quantiles([r["seconds"] for r in rows])
    cpu = quantiles([r["cpu_seconds"] for r in rows])
    print(f"\nseconds per diagnosis ({len(rows)}), wall: " + ", ".join(f"{k} {v:.1f}" for k, v in seconds.items()))
    if cpu:
        print("  CPU (user + system): " + ", ".join(f"{k} {v:.1f}" for k, v in cpu.items()))
        wall, used = sum(r["seconds"] for r in rows), sum(r["cpu_seconds"] or 0 for r in rows)
        print(f"  all diagnoses: {wall:.0f} s wall, {used:.0f} s CPU")
    generating = sum(r["generate_seconds"] for r in rows)
    print(f"writing the datasets: {generating:.0f} s; the bench: {time.perf_counter() - started:.0f} s wall")
    if arguments.json:
        Path(arguments.json).write_text(
            json.dumps(
                {
                    "confusion": confusion,
                    "by_family": by_family,
                    "by_strength": by_strength,
                    "upper_visible": {
                        "min_hidden_gain": VISIBLE_GAIN,
                        "datasets": len(visible),
                        "right": sum(r["outcome"] == "right" for r in visible),
                        "wrong": sum(r["outcome"] == "wrong" for r in visible),
                    },
                    "by_family_and_strength": grid,
                    "nulls": {
                        "verdicts": dict(null_verdicts),
                        "force_over_noise": force,
                        "pressure_over_noise": pressure,
                    },
                    "misses": dict(misses),
                    "named_gains": gains,
                    "seconds": seconds,
                    "cpu_seconds": cpu,
                    "rows": rows,
                },
                indent=2,
                default=float,
            )
            + "\n"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
