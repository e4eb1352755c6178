#!/usr/bin/env bash
# Issue 13's score: `drillwave diagnose` on all 12 synthetic recordings of ../shared, each scored against the KEY
# (every concealed effect named, nothing on the base recording, the held-out error lower after than before).
# Prints one line per recording; exits non-zero while any recording fails. About 30 s per recording on 2 cores
# (CI runs it after the tests).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target drillwave_apps_tests drillwave_cli
log=$(mktemp)
status=0
build/bin/drillwave_apps_tests --gtest_filter='Recordings/SyntheticScoring.*' >"$log" 2>&1 || status=$?
grep -E '^\[ +(measured|FAILED|PASSED) ' "$log" || true
rm -f "$log"
exit "$status"
