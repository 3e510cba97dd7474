#!/usr/bin/env bash
# Type-checks the public Python API with mypy, strict: the modules that make it and a user's calls
# to it (tests/typecheck/public_api.py), against the package's annotations and the compiled core's
# stubs (settings: pyproject.toml's [tool.mypy]). mypy and pandas-stubs come with the dev extra
# (scripts/install-deps.sh installs them in .venv).
# Usage: scripts/typecheck.sh
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x .venv/bin/mypy ]; then
  echo "error: mypy is missing from .venv: run scripts/install-deps.sh" >&2
  exit 1
fi
.venv/bin/mypy
