#!/usr/bin/env bash
# Installs everything pamkit needs on a fresh Debian 12 machine: the C++ toolchain and
# libraries from Debian's packages, the Python build and test tools from PyPI.
# Usage: scripts/install-deps.sh        (as root, or with sudo available)
set -euo pipefail

apt_packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libboost-dev libsundials-dev catch2 libserialport-dev
)
python_packages=(
  "scikit-build-core>=0.8" "pybind11>=2.12" "numpy>=1.24" "scipy>=1.10"
  "matplotlib>=3.7" "pytest>=7"
)

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${apt_packages[@]}"

python3 -m pip install --quiet --upgrade pip
python3 -m pip install --quiet "${python_packages[@]}"
