#!/usr/bin/env bash
# Formats the sources in place: clang-format (.clang-format) on the tracked C and C++ files, then
# ruff format and ruff check --fix (pyproject.toml's [tool.ruff]) on the Python files.
# scripts/lint.sh checks the same without changing anything.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/style_tools.sh
require_pinned_tools

cxx_sources | xargs -d '\n' "$clang_format" -i --style=file
ruff format --quiet .
# Fixes what ruff can fix safely; reports the rest (and fails) for a person to fix.
ruff check --fix --quiet .
