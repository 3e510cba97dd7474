"""pamkit template KIND [-o EXPERIMENT.toml]: an experiment file with every key explained."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path


def register(subparsers) -> None:
    from pamkit.reference import KIND_MEANINGS
    from pamkit.templates import TEMPLATE_KINDS

    kinds = "; ".join(f"{kind}: {KIND_MEANINGS.get(kind, 'several tests of one muscle')}" for kind in TEMPLATE_KINDS)
    parser = subparsers.add_parser(
        "template",
        help="write an experiment file of a kind of test, every key explained (unit, meaning, default)",
        description=f"Kinds: {kinds}.",
    )
    parser.add_argument("kind", choices=TEMPLATE_KINDS, help="the kind of test")
    parser.add_argument(
        "-o",
        "--output",
        metavar="EXPERIMENT.toml",
        help="write it here, with a data CSV of the kind's header row beside it (default: print the TOML)",
    )
    parser.add_argument("--force", action="store_true", help="overwrite existing files")
    parser.set_defaults(run=run)


def run(arguments: argparse.Namespace) -> int:
    from pamkit.reference import data_columns
    from pamkit.templates import template

    if arguments.output is None:
        sys.stdout.write(template(arguments.kind))
        return 0
    toml = Path(arguments.output)
    csv = toml.with_suffix(".csv")
    written = [toml] if arguments.kind == "campaign" else [toml, csv]
    for path in written:
        if path.exists() and not arguments.force:
            raise ValueError(f"{path} exists: choose another name, or --force to overwrite it")
    toml.parent.mkdir(parents=True, exist_ok=True)
    toml.write_text(template(arguments.kind, data=csv.name), encoding="utf-8")
    if arguments.kind != "campaign":
        csv.write_text(",".join(c.name for c in data_columns(arguments.kind) if c.required) + "\n", encoding="utf-8")
    print("wrote " + " and ".join(str(p) for p in written))
    return 0
