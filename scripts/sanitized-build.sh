#!/usr/bin/env bash
# One clang build with AddressSanitizer + UndefinedBehaviorSanitizer (and libFuzzer's coverage) in build-fuzz, shared
# by scripts/sanitize.sh (the fast tests under the sanitizers) and scripts/fuzz.sh (the libFuzzer targets), so that CI
# compiles the library once for both. Usage: sanitized-build.sh TARGET... (cmake --build's targets).
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang++ >/dev/null || { echo "$0: needs clang (scripts/install-deps.sh fuzz)" >&2; exit 2; }
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# -O1 and line tables only: ASan's and libFuzzer's usual build, half the compile time of -O2 -g. NDEBUG as in
# RelWithDebInfo. No Python module: an ASan-built extension cannot be loaded into an interpreter built without ASan.
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" \
  -DDRILLWAVE_FUZZ=ON -DDRILLWAVE_BUILD_APPS=ON -DDRILLWAVE_BUILD_TESTS=ON -DDRILLWAVE_PYTHON=OFF \
  -DDRILLWAVE_INSTALL=OFF >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build build-fuzz -j"$(nproc)" "${targets[@]}"
