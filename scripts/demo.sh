#!/usr/bin/env bash
# The main job on bundled data: simulate the thesis's bench test of table C.2 (PAM 2 inflated to
# 207 kPa, stretched to 90 %, 10 cycles at 2.5 mm/s) and write out/demo.csv and out/demo.png.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p out
PYTHONPATH="$PWD/build/python" python3 -m pamkit simulate data/experiments/thesis/pam2_207kPa_90pct.toml \
  -o out/demo.csv --plot out/demo.png
