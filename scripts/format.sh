#!/usr/bin/env bash
# Formats the sources in place: clang-format (.clang-format) on the tracked C and C++ files, then
# ruff format and ruff check --fix (pyproject.toml's [tool.ruff]) on the Python files.
# scripts/lint.sh checks the same without changing anything.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/style_tools.sh
require_pinned_tools

# Twice: clang-format 14 lays out some macros of string literals differently on a second pass
# (firmware/pamkit_logger/pamkit_frame.h), and lint.sh checks that a pass changes nothing.
for _ in 1 2; do
  cxx_sources | xargs -d '\n' "$clang_format" -i --style=file
done
# ruff's fixes first (import order, ...), then the formatter, as ruff advises. What ruff cannot fix
# is reported, and this script fails, for a person to fix.
status=0
ruff check --fix --quiet . || status=1
ruff format --quiet .
exit $status
