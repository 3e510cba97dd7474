"""Which decisions changed between two runs of a decision bench: the check a rule change must pass
(the same verdicts on every decision bench, or each change explained).

    python3 bench/decision_diff.py BEFORE.json AFTER.json [--fail-on-change]

Reads the `--json` files bench_diagnose.py, bench_families.py and bench_near_model.py write (both
of one bench, the same datasets). A dataset is keyed by its family (or hidden effect), strength
and seed; its decision is its outcome where the bench scores one (right, partial, honest, wrong)
and the causes its report named. Prints each dataset whose decision changed, old -> new, then how
many changed of how many; a dataset in one file only is listed as such. `--fail-on-change` exits 1
when any changed. Needs only the standard library: the JSON files are the whole interface.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

Key = tuple[str, str, int]
Decision = tuple[str, tuple[str, ...]]


def decisions(path: Path) -> dict[Key, Decision]:
    """Every dataset's decision in one bench's `--json` file, by dataset."""
    document = json.loads(path.read_text())
    rows = document["rows"] if isinstance(document, dict) else document
    out: dict[Key, Decision] = {}
    for row in rows:
        if "family" in row:  # bench_families, bench_near_model
            key = (row["family"], row.get("strength") or "", int(row["seed"]))
        else:  # bench_diagnose: the hidden effect is the dataset's family
            key = (row["truth"], "", int(row["seed"]))
        named = row.get("named")
        if named is None:
            named = [] if row.get("cause") in (None, "none", "unexplained") else [row["cause"]]
        out[key] = (row.get("outcome", row.get("cause", "")), tuple(sorted(named)))
    return out


def changes(before: dict[Key, Decision], after: dict[Key, Decision]) -> list[tuple[Key, object, object]]:
    """The datasets whose decision differs, or that one run lacks, in key order."""
    keys = sorted(set(before) | set(after))
    return [(k, before.get(k, "missing"), after.get(k, "missing")) for k in keys if before.get(k) != after.get(k)]


def describe(decision) -> str:
    if decision == "missing":
        return "(not in this run)"
    outcome, named = decision
    return f"{outcome} [{', '.join(named) or 'nothing named'}]"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("before", type=Path, help="the bench's --json file before the change")
    parser.add_argument("after", type=Path, help="the same bench's --json file after it")
    parser.add_argument("--fail-on-change", action="store_true", help="exit 1 if any decision changed")
    arguments = parser.parse_args(argv)
    before, after = decisions(arguments.before), decisions(arguments.after)
    changed = changes(before, after)
    for (family, strength, seed), old, new in changed:
        where = f"{family} {strength} seed {seed}".replace("  ", " ")
        print(f"{where}: {describe(old)} -> {describe(new)}")
    print(f"{len(changed)} of {len(set(before) | set(after))} decisions changed")
    return 1 if changed and arguments.fail_on_change else 0


if __name__ == "__main__":
    sys.exit(main())
