"""pamkit effects: list the effect catalog."""

from __future__ import annotations

import argparse


def register(subparsers) -> None:
    parser = subparsers.add_parser("effects", help="list the effect catalog: parameters, units, what gives each away")
    parser.set_defaults(run=run)


def run(arguments: argparse.Namespace) -> int:
    from pamkit.effects import describe

    print(describe())
    return 0
