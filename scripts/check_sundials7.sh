#!/usr/bin/env bash
# Builds pamkit's library and C++ unit tests against SUNDIALS 7 and runs the tests, on a machine
# whose system SUNDIALS is 6 (Debian 12). SUNDIALS 7 comes from PyPI: the official Python
# bindings' wheel (sundials4py 7.9.0) ships the headers, the static libraries and the CMake
# package files.
#
# Those static libraries were built for the Python module: on destruction they call five
# functions that free Python callback tables, defined in the module itself. pamkit never creates
# such tables (their pointers stay NULL), so this script links the tests with empty definitions
# of the five. That is the only difference from a SUNDIALS 7 installed by Homebrew or conda.
#
# Usage: scripts/check_sundials7.sh [WORK_DIR]   (default: a temporary folder, removed at the end)
#   about 2 minutes on 2 cores: the unit tests are compiled again.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
version=7.9.0
if [ $# -ge 1 ]; then
  work=$1
  mkdir -p "$work"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi

if [ ! -f "$work/sundials/lib64/cmake/sundials/SUNDIALSConfig.cmake" ]; then
  "${PYTHON:-$root/.venv/bin/python}" -m pip download "sundials4py==$version" --no-deps --only-binary :all: --python-version 3.12 \
    --platform "manylinux_2_28_$(uname -m)" -d "$work/wheel" --quiet
  python3 -m zipfile -e "$work"/wheel/sundials4py-*.whl "$work/sundials"
fi

cat > "$work/python_table_destructors.c" <<'EOF'
/* Empty stand-ins for the sundials4py module's destructors of Python callback tables, which
   the wheel's static libraries call with NULL when no table was made (see check_sundials7.sh). */
void SUNContextFunctionTable_Destroy(void* table) { (void)table; }
void SUNLinearSolverFunctionTable_Destroy(void* table) { (void)table; }
void SUNLoggerFunctionTable_Destroy(void* table) { (void)table; }
void SUNNonlinearSolverFunctionTable_Destroy(void* table) { (void)table; }
void cvode_user_supplied_fn_table_destroy(void* table) { (void)table; }
EOF
cc -c -O2 "$work/python_table_destructors.c" -o "$work/python_table_destructors.o"

cmake -S "$root" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPAMKIT_WERROR=ON \
  -DSUNDIALS_DIR="$work/sundials/lib64/cmake/sundials" -DCMAKE_PREFIX_PATH="$work/sundials" \
  -DPAMKIT_BUILD_PYTHON=OFF -DPAMKIT_BUILD_FIRMWARE=OFF \
  -DCMAKE_EXE_LINKER_FLAGS="$work/python_table_destructors.o" >"$work/configure.log"
found=$(sed -n 's/^#define SUNDIALS_VERSION "\(.*\)"/\1/p' "$work/sundials/include/sundials/sundials_config.h")
echo "SUNDIALS $found from the sundials4py $version wheel"
cmake --build "$work/build" -j2 --target pamkit_unit_tests
"$work/build/tests/pamkit_unit_tests"
