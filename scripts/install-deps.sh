#!/usr/bin/env bash
# Installs the Debian 12 packages drillwave needs, only those that are missing (run as root, or with sudo).
set -euo pipefail
# NLopt: the fits of diagnosis. The Python module and its tests: pybind11-dev python3-dev (build), python3-numpy
# python3-pytest (run), python3-distributed (drillwave_dask's tests on a real Dask cluster). Chromium (headless): the
# test that opens diagnose's report.html.
packages=(g++ cmake make libeigen3-dev libboost-dev nlohmann-json3-dev libcli11-dev libgtest-dev libnlopt-cxx-dev
          pybind11-dev python3-dev python3-numpy python3-pytest python3-distributed chromium)
# `install-deps.sh fuzz` adds clang for the libFuzzer targets (scripts/fuzz.sh).
[[ "${1:-}" == fuzz ]] && packages+=(clang libclang-rt-dev)  # libFuzzer's runtime is only recommended by clang
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "drillwave: installing ${missing[*]}"
  sudo_cmd=""
  [[ $(id -u) -ne 0 ]] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
