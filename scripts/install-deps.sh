#!/usr/bin/env bash
# Installs the Debian 12 packages drillwave needs, only those that are missing (run as root, or with sudo).
set -euo pipefail
# `install-deps.sh main`: what the main job (scripts/run-default.sh: build the tool, run the default case) needs: the
# compiler and CMake, Eigen, Boost (odeint), nlohmann-json, CLI11, NLopt (the fits of diagnosis) and GoogleTest
# (the build configures its tests). Without an argument, what the tests need besides: the Python module and its tests
# (pybind11-dev python3-dev to build, python3-numpy python3-pytest to run, python3-distributed for drillwave_dask's
# tests on a real Dask cluster) and Chromium (headless: the test that opens diagnose's report.html, about 190 MB).
packages=(g++ cmake make libeigen3-dev libboost-dev nlohmann-json3-dev libcli11-dev libgtest-dev libnlopt-cxx-dev)
[[ "${1:-}" != main ]] && packages+=(pybind11-dev python3-dev python3-numpy python3-pytest python3-distributed chromium)
# `install-deps.sh fuzz` adds clang for the libFuzzer targets (scripts/fuzz.sh).
[[ "${1:-}" == fuzz ]] && packages+=(clang libclang-rt-dev)  # libFuzzer's runtime is only recommended by clang
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "drillwave: installing ${missing[*]} (apt-get; a few minutes on a fresh system)"
  sudo_cmd=""
  [[ $(id -u) -ne 0 ]] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
