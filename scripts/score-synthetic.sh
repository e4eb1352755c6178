#!/usr/bin/env bash
# Issue 32's score: `drillwave diagnose` on the synthetic recordings of ../shared, scored against their KEY, which only
# scripts/score_recordings.py reads, never the tool. It prints one line per recording, then precision (named effects
# that are concealed), recall (concealed effects that are named), names on base recordings and recordings named
# without a lower held-out error; it exits non-zero below the floors given here or on any of the latter two.
#   bash scripts/score-synthetic.sh        the 12 recordings of synthetic/ (CI; 33 min on 2 cores)
#   bash scripts/score-synthetic.sh all    and the 36 of synthetic-train/ (~2 h)
# The floors guard against losing ground: this code measured precision 0.917 (11 of 12) and recall 0.846 (11 of 13)
# on synthetic/ with BASELINE.md's rock heterogeneity in the base case (docs/diagnosis.md); one more miss (10 of 13 =
# 0.769) or one more false name (11 of 13 = 0.846) does not pass. A change of the models' rounding alone moves these
# decisions (docs/results.md, "A rounding-level change of the rock": 0.818 and 0.692), so a change to the numerics
# needs this score run before it lands. Issue 32 asks for precision >= 0.9 and recall >= 0.85 over all 48.
# Where ../shared is absent it says so and passes.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target drillwave_cli
sets=(--set ../shared/recordings/synthetic)
[[ "${1:-}" == all ]] && sets+=(--set ../shared/recordings/synthetic-train)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# Two recordings at a time, each with two threads: while both run they share the cores; the last one left, often the
# longest, then has both (diagnosis.json is the same at any -j). At -j 1 the dev twelve's times queued to 3 442 s in
# their order, rec12's 1 313 s last, against 2 822 s of work per core; at -j 2 the twelve took 1 979 s wall, rec12
# 437 s, with the same names and errors.
python3 scripts/score_recordings.py "${sets[@]}" --binary build/bin/drillwave --out "$out" --parallel 2 -j 2 \
    --min-precision "${SCORE_MIN_PRECISION:-0.9}" --min-recall "${SCORE_MIN_RECALL:-0.84}" --strict
