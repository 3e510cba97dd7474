"""The ``pamkit`` command line. Subcommands live in ``pamkit.commands``, one module per area."""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys

import pamkit.commands
from pamkit.experiment import ExperimentError


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="pamkit", description="Simulate and test pneumatic artificial muscles.")
    subparsers = parser.add_subparsers(dest="command", required=True)
    for module in sorted(pkgutil.iter_modules(pamkit.commands.__path__), key=lambda m: m.name):
        importlib.import_module(f"pamkit.commands.{module.name}").register(subparsers)
    return parser


def main(argv: list[str] | None = None) -> int:
    arguments = build_parser().parse_args(argv)
    try:
        return arguments.run(arguments)
    except (ExperimentError, ValueError) as error:
        print(f"pamkit {arguments.command}: error: {error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"pamkit {arguments.command}: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
