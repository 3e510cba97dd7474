#!/usr/bin/env bash
# Installs everything pamkit needs on a fresh Debian 12 machine: the C++ toolchain and
# libraries from Debian's packages (fixed by the release), and the Python build, runtime, test
# and lint packages from PyPI into the project's venv, .venv, at the versions pinned in
# constraints.txt. Safe to run again: it installs only what is missing or changed.
# Usage: scripts/install-deps.sh            (as root, or with sudo available)
#        scripts/install-deps.sh --latest   the newest versions PyPI serves, in .venv-latest
#                                           (the drift check: scripts/test.sh --latest)
set -euo pipefail
cd "$(dirname "$0")/.."

latest=false
if [ "${1:-}" = "--latest" ]; then latest=true; fi

apt_packages=(
  build-essential cmake ninja-build pkg-config python3 python3-dev python3-venv
  libeigen3-dev libboost-dev libsundials-dev catch2 libserialport-dev
  libtomlplusplus-dev  # the muscle-parameters file (include/pamkit/io/params_file.hxx), headers only
  gcc-avr avr-libc arduino-core-avr avrdude simavr libsimavr-dev clang libclang-rt-14-dev arduino-builder  # logger firmware, upload, tests
  clang-format  # scripts/format.sh and lint.sh (Debian 12's 14)
  doxygen  # scripts/docs.sh: the C++ API from the headers
)

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

missing=()
for package in "${apt_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing Debian packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# What the project asks of PyPI, read from pyproject.toml (build-system, runtime and every extra:
# test, scale, dev, docs, wheel) so that the lower bounds live in one place; constraints.txt fixes
# the versions.
if $latest; then venv=.venv-latest; else venv=.venv; fi
if [ ! -x "$venv/bin/python" ]; then
  echo "creating the Python venv $venv"
  python3 -m venv "$venv"
fi
mapfile -t requirements < <("$venv/bin/python" - <<'PY'
import tomllib
with open("pyproject.toml", "rb") as f:
    project = tomllib.load(f)
for requirement in (project["build-system"]["requires"] + project["project"]["dependencies"]
                    + [r for extra in project["project"]["optional-dependencies"].values() for r in extra]):
    print(requirement)
PY
)
pip=("$venv/bin/python" -m pip --disable-pip-version-check --quiet)
if $latest; then
  # The newest of everything, every time: that is what the drift check is for.
  echo "installing the newest Python packages into $venv"
  "${pip[@]}" install --upgrade --upgrade-strategy eager "${requirements[@]}"
  "${pip[@]}" freeze
else
  # A copy of the constraints the venv was installed with: unchanged means nothing to do.
  stamp="$venv/pamkit-constraints.txt"
  if ! cmp -s constraints.txt "$stamp"; then
    echo "installing the pinned Python packages (constraints.txt) into $venv"
    "${pip[@]}" install -c constraints.txt "${requirements[@]}"
    cp constraints.txt "$stamp"
  fi
fi
