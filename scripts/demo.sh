#!/usr/bin/env bash
# The main job on bundled data: diagnose a bench test with an effect hidden in it
# (data/experiments/example) and write the report (out/report.json) and its figure
# (out/report.png). The verdict is printed; data/experiments/example/manifest.json holds the truth.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p out
PYTHONPATH="$PWD/build/python" .venv/bin/python -m pamkit diagnose data/experiments/example/experiment.toml \
  --json out/report.json --plot out/report.png
