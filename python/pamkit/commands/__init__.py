"""Subcommands of the ``pamkit`` command line, one module per area.

Each module defines ``register(subparsers)``, which adds its subcommand(s) with a ``run``
default taking the parsed arguments and returning an exit code. ``pamkit.cli`` finds every
module here, so an area adds a command without touching the others.
"""
