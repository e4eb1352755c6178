#!/usr/bin/env bash
# Set up, build and run every test (unit, numerical validation, JSON cases with their expect blocks, bad input).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# The Python module for Debian's interpreter, for which install-deps.sh installed NumPy and pytest (a python3 found
# first on PATH, e.g. pyenv's, may have neither, and its tests would be skipped).
# DRILLWAVE_PYTHON=ON: a build folder first configured by run-default.sh, before pybind11 was installed, keeps the
# module off otherwise.
python=(-DDRILLWAVE_PYTHON=ON)
[[ -x /usr/bin/python3 ]] && python+=(-DPython3_EXECUTABLE=/usr/bin/python3)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${python[@]}" >/dev/null
cmake --build build -j"$(nproc)"
# `scoring`: a label for acceptance scores kept out of the test run (none today; the synthetic recordings' score is
# scripts/score-synthetic.sh). `long`: the README's diagnose examples run in full (docs.readme_run_all, about 8
# minutes); `ctest -L long` runs them. --timeout 900: a test that hangs fails by name after 15 minutes, where CTest's
# default (1500 s) would spend CI's time; the slowest without a timeout of its own took 176 s in a fresh Debian 12.
ctest --test-dir build --output-on-failure -j"$(nproc)" -LE 'scoring|long' --timeout 900
