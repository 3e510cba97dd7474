# Sourced by scripts/format.sh and scripts/lint.sh: the pinned formatters and the files they own.
# Another version of either tool formats differently, so both scripts refuse to run with one.
#   clang-format 14: Debian 12's package (apt-get install clang-format); CLANG_FORMAT names another binary
#   ruff 0.17.6:     pip install ruff==0.17.6 (the same pin as .pre-commit-config.yaml)
clang_format=${CLANG_FORMAT:-clang-format}
# ruff from the project's venv (scripts/install-deps.sh pins it there), else from PATH.
if [ -x .venv/bin/ruff ]; then PATH="$PWD/.venv/bin:$PATH"; fi
clang_format_major=14
ruff_version=0.17.6

require_pinned_tools() {
  local found
  found=$("$clang_format" --version 2>/dev/null | sed -n 's/.*clang-format version \([0-9]*\)\..*/\1/p')
  if [ "$found" != "$clang_format_major" ]; then
    echo "error: clang-format $clang_format_major is needed (Debian 12: apt-get install clang-format);" \
         "found: ${found:-none}" >&2
    return 1
  fi
  found=$(ruff --version 2>/dev/null | sed -n 's/^ruff \(.*\)$/\1/p')
  if [ "$found" != "$ruff_version" ]; then
    echo "error: ruff $ruff_version is needed (pip install ruff==$ruff_version); found: ${found:-none}" >&2
    return 1
  fi
}

# Every tracked C and C++ file is the project's own: the Arduino core and Catch2 come from Debian's
# packages and generated headers are written to the build tree, so none of them is tracked.
cxx_sources() {
  git ls-files -- '*.c' '*.h' '*.cpp' '*.hpp' '*.hxx' '*.ino'
}
