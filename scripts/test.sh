#!/usr/bin/env bash
# Runs every test: installs what is missing, builds, then ctest (C++ unit tests, Python tests,
# the installed-package consumer). Extra arguments go to ctest, e.g. scripts/test.sh -L unit
# Usage: scripts/test.sh [CTEST ARGS]            with the pinned stack (.venv, build/)
#        scripts/test.sh --latest [CTEST ARGS]   the drift check: the same suite with the newest
#                                                versions PyPI serves (.venv-latest, build-latest/)
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
if [ "${1:-}" = "--latest" ]; then
  shift
  build=build-latest
  scripts/build.sh --latest
else
  scripts/build.sh
fi
ctest --test-dir "$build" --output-on-failure --parallel "$(nproc)" "$@"
