#!/usr/bin/env bash
# Installs everything pamkit needs on a fresh Debian 12 machine: the C++ toolchain and
# libraries from Debian's packages, the Python build and test tools from PyPI. Safe to run
# again: it installs only what is missing.
# Usage: scripts/install-deps.sh        (as root, or with sudo available)
set -euo pipefail

apt_packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libboost-dev libsundials-dev catch2 libserialport-dev
  gcc-avr avr-libc arduino-core-avr simavr libsimavr-dev clang libclang-rt-14-dev arduino-builder  # logger firmware and its tests
)
# pybind11 comes from PyPI: Debian 12's 2.10 predates NumPy 2 support (2.12).
python_packages=(
  "scikit-build-core>=0.8" "pybind11>=2.12" "numpy>=1.24" "scipy>=1.10" "matplotlib>=3.7" "pytest>=7"
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

if ! python3 - "${python_packages[@]}" <<'PY' 2>/dev/null
import sys
from importlib.metadata import version
from packaging.requirements import Requirement
for spec in sys.argv[1:]:
    requirement = Requirement(spec)
    if not requirement.specifier.contains(version(requirement.name), prereleases=True):
        sys.exit(1)
PY
then
  echo "installing Python packages: ${python_packages[*]}"
  python3 -m pip install --quiet --disable-pip-version-check --root-user-action=ignore "${python_packages[@]}"
fi
