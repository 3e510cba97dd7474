"""The ``pamkit`` command line. Subcommands live in ``pamkit.commands``, one module per area."""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys
import traceback
import warnings

import pamkit.commands
from pamkit._core import Error, SolverError, __version__

# Exit statuses, as `pamkit --help` lists them.
EXIT_OK = 0
EXIT_BUG = 1  # an error pamkit did not expect: a traceback and a request to report it
EXIT_BAD_INPUT = 2  # a file, a value or an option that cannot be used; the message says which
EXIT_MODEL = 3  # the model or its solver cannot follow the input (e.g. CVODES gave up)
EXIT_INTERRUPTED = 130
EPILOG = """exit status: 0 done; 2 bad input (the message names the file, line or option); 3 the model or its
solver could not follow the input; 130 interrupted; 1 a bug in pamkit (a traceback; please report it)."""


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="pamkit", description="Simulate and test pneumatic artificial muscles.", epilog=EPILOG
    )
    parser.add_argument("--version", action="version", version=f"pamkit {__version__}")
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
    except ValueError as error:  # ExperimentError, LoggerError, InvalidInput, InvalidParameter
        print(f"pamkit {arguments.command}: error: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except OSError as error:  # an output that cannot be written, a file that vanished
        where = f" {error.filename}" if error.filename else ""
        print(f"pamkit {arguments.command}: error:{where}: {error.strerror or error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except (SolverError, Error) as error:
        print(f"pamkit {arguments.command}: the model cannot follow this input: {error}", file=sys.stderr)
        return EXIT_MODEL
    except KeyboardInterrupt:
        print(f"pamkit {arguments.command}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except Exception:  # noqa: BLE001 - the last resort: a bug, shown whole
        traceback.print_exc()
        print(
            f"pamkit {arguments.command}: this is a bug in pamkit; please report it with the command line and "
            "the files it read",
            file=sys.stderr,
        )
        return EXIT_BUG


def command_help() -> list[tuple[str, str]]:
    """Each ``pamkit`` command with its ``--help`` text, ``pamkit`` itself first (from argparse)."""
    parser = build_parser()
    commands = [("pamkit", parser.format_help())]
    for action in parser._actions:  # argparse keeps subcommands in its private action list only
        if isinstance(action, argparse._SubParsersAction):
            commands += [(f"pamkit {name}", sub.format_help()) for name, sub in sorted(action.choices.items())]
    return commands


if __name__ == "__main__":
    sys.exit(main())
