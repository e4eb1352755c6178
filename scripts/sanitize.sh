#!/usr/bin/env bash
# Build with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan and run the fast tests there: memory
# errors and undefined behaviour fail the run (CI runs this after scripts/test.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# No Python module: an ASan-built extension cannot be loaded into an interpreter built without ASan.
# -O1 -g1: ASan's own recommendation, and half the compile time of RelWithDebInfo's -O2 -g (CI builds this tree a
# second time); line tables are enough for its stack traces. NDEBUG as in RelWithDebInfo.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DDRILLWAVE_PYTHON=OFF >/dev/null
cmake --build build-asan -j"$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-asan --output-on-failure -j"$(nproc)" -L fast --timeout 900
