#!/usr/bin/env bash
# Set up, build and run the main job: installs what is missing, builds, and simulates the embedded default case
# (json-cases/saldivar-stickslip.json) into out/default (trajectory.csv, summary.json, plot.svg, report.md).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh main  # the build and the tool only: no Python module, no browser
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target drillwave_cli
./build/bin/drillwave run --out out/default
