"""The ``pamkit`` command line. Subcommands live in ``pamkit.commands``, one module per area."""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys
import warnings

import pamkit.commands
from pamkit.experiment import ExperimentError


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="pamkit", description="Simulate and test pneumatic artificial muscles.")
    subparsers = parser.add_subparsers(dest="command", required=True)
    for module in sorted(pkgutil.iter_modules(pamkit.commands.__path__), key=lambda m: m.name):
        importlib.import_module(f"pamkit.commands.{module.name}").register(subparsers)
    return parser


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    print(f"pamkit: warning: {message}", file=sys.stderr)


def main(argv: list[str] | None = None) -> int:
    arguments = build_parser().parse_args(argv)
    try:
        with warnings.catch_warnings():
            warnings.showwarning = _show_warning  # one line per repair, not Python's source echo
            return arguments.run(arguments)
    except (ExperimentError, ValueError) as error:
        print(f"pamkit {arguments.command}: error: {error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"pamkit {arguments.command}: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
