#!/usr/bin/env bash
# Runs every test: installs what is missing, builds, then ctest (C++ unit tests, Python tests,
# the installed-package consumer). Extra arguments go to ctest, e.g. scripts/test.sh -L unit
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
ctest --test-dir build --output-on-failure --parallel "$(nproc)" "$@"
