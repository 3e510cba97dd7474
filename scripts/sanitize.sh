#!/usr/bin/env bash
# Builds pamkit with AddressSanitizer and UndefinedBehaviorSanitizer in ./build-asan (PAMKIT_ASAN)
# and runs every C++ test there: the Catch2 tests of all areas and the firmware's decoder,
# calibration and simavr end-to-end tests. Not run: the Python tests (the interpreter is not
# sanitized), the installed consumer, the fuzz target (always built with both sanitizers; it runs
# in the ordinary build) and the Arduino IDE build (no host code). Any finding fails the test.
# Extra arguments go to ctest, e.g. scripts/sanitize.sh -L unit
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPAMKIT_ASAN=ON \
  -DPAMKIT_BUILD_PYTHON=OFF -DPAMKIT_BUILD_BENCH=OFF >/dev/null
cmake --build build-asan --parallel "$(nproc)"
export ASAN_OPTIONS=detect_stack_use_after_return=1:strict_init_order=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
ctest --test-dir build-asan --output-on-failure --parallel "$(nproc)" \
  --label-exclude '^(python|install)$' --exclude-regex '^firmware_(fuzz_decoder|arduino_ide_build)$' "$@"
