#!/usr/bin/env bash
# Checks formatting and lint without changing anything: exits non-zero and names every file that
# scripts/format.sh would change, and every ruff finding. Same tools and settings as format.sh.
set -uo pipefail
cd "$(dirname "$0")/.."
source scripts/style_tools.sh
require_pinned_tools || exit 2

status=0
unformatted=()
while IFS= read -r file; do
  "$clang_format" --style=file "$file" | cmp -s - "$file" || unformatted+=("$file")
done < <(cxx_sources)
if [ ${#unformatted[@]} -gt 0 ]; then
  echo "clang-format would change ${#unformatted[@]} file(s):"
  printf '  %s\n' "${unformatted[@]}"
  status=1
fi
if ! ruff format --check . ; then
  status=1
fi
if ! ruff check --output-format concise . ; then
  status=1
fi
if [ $status -ne 0 ]; then
  echo "lint failed: run scripts/format.sh, then fix by hand what ruff check still reports" >&2
fi
exit $status
