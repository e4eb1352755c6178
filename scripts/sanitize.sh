#!/usr/bin/env bash
# The fast tests under AddressSanitizer + UBSan: memory errors and undefined behaviour fail the run (CI runs this
# after scripts/test.sh). The build is clang's, in build-fuzz, shared with scripts/fuzz.sh (scripts/sanitized-build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh fuzz
bash scripts/sanitized-build.sh all
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-fuzz --output-on-failure -j"$(nproc)" -L fast --timeout 900
