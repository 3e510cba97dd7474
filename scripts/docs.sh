#!/usr/bin/env bash
# Builds the documentation site into build/docs/html (open build/docs/html/index.html): the
# reference generated from pamkit's own field lists, the Python API from its docstrings, the C++
# API from its headers (Doxygen's XML through breathe), and the gallery, every example of
# examples/gallery run on the bundled data. Every Sphinx or Doxygen warning is an error, and the
# links inside the site are checked (Sphinx's linkcheck; links to other sites are not: CI has no
# network). Needs the build (scripts/build.sh) and the docs extra (scripts/install-deps.sh).
# Usage: scripts/docs.sh
set -euo pipefail
cd "$(dirname "$0")/.."
build=${PAMKIT_BUILD_DIR:-build}
if ! ls "$build"/python/pamkit/_core*.so >/dev/null 2>&1; then
  echo "error: no compiled module in $build/python/pamkit: build first (scripts/build.sh)" >&2
  exit 1
fi
for tool in .venv/bin/sphinx-build doxygen; do
  command -v "$tool" >/dev/null || { echo "error: $tool is missing: run scripts/install-deps.sh" >&2; exit 1; }
done
out=$build/docs
rm -rf "$out" docs/auto_examples
mkdir -p "$out"

# The C++ headers, as Doxygen's XML (warnings fail it: WARN_AS_ERROR in docs/Doxyfile).
{ cat docs/Doxyfile; echo "OUTPUT_DIRECTORY = $out/doxygen"; echo "INPUT += $build/generated/include/pamkit/version.hpp"; echo "STRIP_FROM_PATH += $build/generated/include/pamkit"; } | doxygen -

export PYTHONPATH="$PWD/$build/python" PAMKIT_SOURCE_DIR="$PWD" MPLBACKEND=Agg PAMKIT_DOXYGEN_XML="$PWD/$out/doxygen/xml"
# One BLAS thread: the gallery's diagnoses run beside the build's other work.
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
.venv/bin/sphinx-build -W --keep-going -q -b html -d "$out/doctrees" docs "$out/html"
.venv/bin/sphinx-build -W --keep-going -q -b linkcheck -d "$out/doctrees" docs "$out/linkcheck"
echo "docs: $out/html/index.html"
