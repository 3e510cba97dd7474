#!/usr/bin/env bash
# Configures and builds pamkit (library, Python extension, tests, benchmarks) in ./build with the
# project venv's Python (.venv, pinned by constraints.txt), installing what is missing first.
# Usage: scripts/build.sh            pinned stack: .venv, build/
#        scripts/build.sh --latest   newest PyPI versions: .venv-latest, build-latest/
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--latest" ]; then venv=.venv-latest build=build-latest; else venv=.venv build=build; fi
scripts/install-deps.sh "$@"
# The venv's interpreter builds the extension and runs every pytest under ctest.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE="$PWD/$venv/bin/python" >/dev/null
cmake --build "$build" --parallel "$(nproc)"
