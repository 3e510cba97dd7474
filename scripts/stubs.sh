#!/usr/bin/env bash
# Writes the type stubs of the compiled module with pybind11-stubgen 3.0.0 (pip install
# pybind11-stubgen==3.0.0) from the module already built in build/python: build first
# (scripts/build.sh), run this after changing the bindings, and commit the stubs.
# _core has a submodule (logger), so its stubs are a package: python/pamkit/_core/__init__.pyi and
# logger.pyi. Python still imports the compiled _core (the folder has no __init__.py).
# Usage: scripts/stubs.sh [OUTPUT]    OUTPUT (a folder) defaults to python/pamkit/_core
#   PAMKIT_BUILD_DIR  the build tree holding python/pamkit/_core*.so (default: build)
#   PYTHON            the interpreter the module was built for (default: python3)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
output=${1:-$root/python/pamkit/_core}
build=${PAMKIT_BUILD_DIR:-$root/build}
python=${PYTHON:-python3}
stubgen_version=3.0.0

found=$("$python" -c 'import importlib.metadata as m; print(m.version("pybind11-stubgen"))' 2>/dev/null || true)
if [ "$found" != "$stubgen_version" ]; then
  echo "error: pybind11-stubgen $stubgen_version is needed (pip install pybind11-stubgen==$stubgen_version);" \
       "found: ${found:-none}" >&2
  exit 1
fi
if ! ls "$build"/python/pamkit/_core*.so >/dev/null 2>&1; then
  echo "error: no compiled module in $build/python/pamkit: build first (scripts/build.sh)" >&2
  exit 1
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# --exit-code: a signature stubgen cannot write (a C++ type pybind11 did not know yet) is an error.
# A default value whose repr is not Python (`<pamkit._core.Simulator object at 0x...>`) is written
# `= ...`, as stubs write defaults; every enum is bound in pamkit._core itself.
PYTHONPATH="$build/python" "$python" -m pybind11_stubgen --exit-code --output-dir "$work" \
  --ignore-invalid-expressions '^<pamkit\._core\.\w+ object at 0x[0-9a-f]+>$' \
  --enum-class-locations '.+:pamkit._core' \
  pamkit._core
mkdir -p "$output"
rm -f "$output"/*.pyi  # a submodule removed from the bindings loses its stub
cp "$work"/pamkit/_core/*.pyi "$output"/
# The version is kept in CMakeLists.txt alone: the stub gives its type, not its value.
sed -i -E "s/^__version__: str = .*/__version__: str/" "$output"/__init__.pyi
