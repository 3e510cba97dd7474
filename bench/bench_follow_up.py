"""What the test a report asks for shows, once run: the near-model world's sealed tests whose report
names a test to tell two causes apart, to confirm a cause against a close rival or to check for an
instrument's error, that test run on the same muscle by the same generator, and the two diagnosed
as one campaign.

    PYTHONPATH=build/python python3 bench/bench_follow_up.py [--seeds 3] [--first-seed 1]
        [--nulls 10] [--families a,b] [--strengths weak,medium,strong] [--jobs 1] [--threads 1]
        [--json OUT.json] [--timeout 900]

The datasets are bench_near_model.py's (tests/independent/near_families.py, never importing
pamkit), diagnosed the same way, through files only. Where a report's `separation` names a test
that separates (`separates`: the two models differ there by twice the noise) and that test is
another inflation or the same stretches faster or slower, the generator writes it on the same
muscle, departures and causes (near_families.sealed_test's `variant`); a campaign TOML names the
two, and `python -m pamkit diagnose` reads it. A zero run is written beside the same test
(`[test] zero`), which is diagnosed again, zeroed, alone; an instrument whose offset it read
beyond one sample's noise (the zeroed report's estimate) counts as named, since the report says
what it read and took off, and what it read is printed beside the hidden instruments' errors.
Each dataset is scored as bench_near_model.py scores it (right / wrong / partial / honest), alone
and with the test; printed: the outcomes before and after, by what the test was for, how many
changed from what to what, and the upper strengths' right and all wrong names.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from bench_near_model import (  # the same datasets, diagnosed and scored alike
    add_world_arguments,
    classify,
    diagnose,
    named_causes,
    outcome_of,
    work_list,
)
from independent.near_families import FAMILIES, variant_asked

OUTCOMES = ("right", "partial", "honest", "wrong", "error")
# the instruments whose offsets a zero run reads, and the channel each reads
ZEROED_CAUSES = {"load_cell": "force_N", "sensor_offset": "gauge_pressure_Pa"}


def variant_of(separation: dict | None) -> dict | None:
    """The generator's `variant` for the test a report's separation names, or None where it names
    none or it does not separate."""
    if not separation or not separation.get("separates"):
        return None
    return variant_asked(separation.get("test"))


def follow_up(item, scratch: Path, arguments) -> dict:
    name, seed, strength = item
    folder = scratch / f"{name}-{strength}-{seed}"
    dataset = FAMILIES[name].make(seed, folder / "first", strength)
    alone = diagnose(dataset.experiment, arguments.timeout, arguments.threads)
    row = {"family": name, "seed": seed, "strength": strength, "hidden": list(dataset.hidden)}
    row["alone"] = classify(dataset, alone)
    row["seconds"] = alone["seconds"]
    separation = alone.get("report", {}).get("separation")
    row["purpose"] = separation.get("purpose") if separation else None
    row["asked"] = separation.get("test") if separation else None
    variant = variant_of(separation)
    row["variant"] = variant
    if variant is None:
        return row
    second = FAMILIES[name].make(seed, folder / "second", strength, variant)  # the test asked for
    if variant.get("zero_run"):
        # The same test with its zero run: diagnosed alone, zeroed (a campaign would count it twice).
        zeroed = diagnose(second.experiment, arguments.timeout, arguments.threads)
        row["campaign"] = classify(dataset, zeroed)
        row["instruments"] = {c: dataset.truth["cause"][c] for c in ZEROED_CAUSES if c in dataset.truth["cause"]}
        if "report" in zeroed:
            report = zeroed["report"]
            row["zero_read"] = next((n["offsets"] for n in report["warnings"] if "offsets" in n), {})
            # An offset the zero run read beyond one sample's noise is found: the report says so
            # (`over_noise`) and took it off the data.
            over = next((n["over_noise"] for n in report["warnings"] if "over_noise" in n), {})
            found = {cause: None for cause, channel in ZEROED_CAUSES.items() if over.get(channel, 0.0) > 1.0}
            row["campaign"]["zero_found"] = sorted(found)
            named = {**named_causes(report), **found}
            row["campaign"]["outcome"] = outcome_of(dataset.hidden, dataset.present, named)
        row["seconds"] += zeroed["seconds"]
        return row
    campaign = folder / "campaign.toml"
    campaign.write_text('[campaign]\ntests = ["first/test.toml", "second/test.toml"]\n')
    both = diagnose(campaign, arguments.timeout, arguments.threads)
    row["campaign"] = _scored(dataset, both)
    row["seconds"] += both["seconds"]
    return row


def _scored(dataset, outcome: dict) -> dict:
    """A campaign's report scored as one test's: its named causes against the truth (classify reads
    a test's own evidence, which a campaign's report keeps per test)."""
    if "error" in outcome:
        return classify(dataset, outcome)
    report = outcome["report"]
    first = report["per_test"][0]
    scored = classify(dataset, {"report": {**first, "cause": report["cause"], "causes": report["causes"]}})
    scored["verdict"] = report["verdict"]
    return scored


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_world_arguments(parser)
    parser.add_argument("--json", help="write every dataset's row")
    arguments = parser.parse_args()
    arguments.quick = False  # work_list's fast subset holds supplied sweeps too: not offered here
    items = [item for item in work_list(arguments) if FAMILIES[item[0]].kind == "sealed"]
    started = time.perf_counter()
    with tempfile.TemporaryDirectory() as scratch:

        def run(item):
            row = follow_up(item, Path(scratch), arguments)
            after = row.get("campaign", {}).get("outcome", "-")
            print(
                f"{row['family']:30s} {row['strength'] or 'null':6s} seed {row['seed']:3d}: "
                f"{row['alone']['outcome']:7s} -> {after:7s} {row['purpose'] or ''} {row['variant'] or ''}",
                file=sys.stderr,
                flush=True,
            )
            return row

        with ThreadPoolExecutor(max_workers=max(1, arguments.jobs)) as pool:
            rows = list(pool.map(run, items))

    asked = [r for r in rows if r["asked"]]
    run = [r for r in asked if "campaign" in r]
    print(f"{len(rows)} sealed tests; {len(asked)} reports name a test; {len(run)} of those run")
    table = {}
    for purpose in sorted({r["purpose"] for r in run}):
        group = [r for r in run if r["purpose"] == purpose]
        before = Counter(r["alone"]["outcome"] for r in group)
        after = Counter(r["campaign"]["outcome"] for r in group)
        table[purpose] = {"datasets": len(group), "alone": dict(before), "campaign": dict(after)}
        print(
            f"  {purpose:8s} {len(group):3d}: alone "
            + " ".join(f"{k} {before[k]}" for k in OUTCOMES if before[k])
            + "  ->  with the test asked for "
            + " ".join(f"{k} {after[k]}" for k in OUTCOMES if after[k])
        )
    changed = Counter((r["alone"]["outcome"], r["campaign"]["outcome"]) for r in run)
    print(
        "changes, alone -> campaign: " + ", ".join(f"{a}->{b} {n}" for (a, b), n in sorted(changed.items()) if a != b)
    )
    for r in (r for r in run if "zero_read" in r):
        read = {c: round(v, 1) for c, v in (r["zero_read"] or {}).items()}
        print(
            f"  zero run, {r['family']} {r['strength']} seed {r['seed']}: read {read}, found "
            f"{r['campaign'].get('zero_found')}; hidden {r['instruments']}"
        )
    upper = [r for r in rows if r["strength"] in ("medium", "strong")]
    right_alone = sum(r["alone"]["outcome"] == "right" for r in upper)
    right_after = sum(r.get("campaign", r["alone"])["outcome"] == "right" for r in upper)
    wrong_alone = sum(r["alone"]["outcome"] == "wrong" for r in rows)
    wrong_after = sum(r.get("campaign", r["alone"])["outcome"] == "wrong" for r in rows)
    print(
        f"upper two strengths: {right_alone}/{len(upper)} right alone, {right_after}/{len(upper)} with every "
        f"test asked for run; wrong names over all {len(rows)}: {wrong_alone} alone, {wrong_after} with the tests"
    )
    print(f"the bench: {time.perf_counter() - started:.0f} s wall")
    if arguments.json:
        Path(arguments.json).write_text(json.dumps({"by_purpose": table, "rows": rows}, indent=2, default=float) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
