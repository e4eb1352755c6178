#!/usr/bin/env bash
# Issue 32's score: `drillwave diagnose` on the synthetic recordings of ../shared, scored against their KEY, which only
# scripts/score_recordings.py reads, never the tool. It prints one line per recording, then precision (named effects
# that are concealed), recall (concealed effects that are named), names on base recordings and recordings named
# without a lower held-out error; it exits non-zero below the floors given here or on any of the latter two.
#   bash scripts/score-synthetic.sh        the 12 recordings of synthetic/ (about 35 min on 2 cores)
#   bash scripts/score-synthetic.sh ci     CI's seven of them (541 s): the base recording and the six whose
#                                          diagnosis takes under 5 minutes (rec03, rec05-rec10: soft top drive, axial
#                                          decoupling, side friction, Stribeck with a telemetry delay, Stribeck,
#                                          Kelvin-Voigt). Left to the full run: rec01-02, rec04 (the bouncing bit,
#                                          22 min alone), rec11-12, which with the rest took 35 min of CI's 90.
#   bash scripts/score-synthetic.sh all    and the 36 of synthetic-train/ (~2 h)
# The floors guard against losing ground: the twelve score precision 1.000 and recall 1.000 (docs/results.md); one
# miss among CI's seven effects (6 of 7 = 0.857) still passes the recall floor, two do not; one false name (7 of 8 =
# 0.875) fails the precision floor. A change of the models' rounding alone moves these decisions (docs/results.md, "A
# rounding-level change of the rock"), so a change to the numerics needs the full run before it lands. Issue 32 asks
# for precision >= 0.9 and recall >= 0.85 over all 48.
# Where ../shared is absent it says so and passes.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target drillwave_cli
sets=(--set ../shared/recordings/synthetic)
case "${1:-}" in
  all) sets+=(--set ../shared/recordings/synthetic-train) ;;
  ci) sets+=(--only rec03,rec05,rec06,rec07,rec08,rec09,rec10) ;;
  "") ;;
  *) echo "score-synthetic.sh: unknown argument '$1' (expected nothing, ci or all)" >&2; exit 2 ;;
esac
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# Two recordings at a time, each with two threads: while both run they share the cores; the last one left, often the
# longest, then has both (diagnosis.json is the same at any -j). At -j 1 the dev twelve's times queued to 3 442 s in
# their order, rec12's 1 313 s last, against 2 822 s of work per core; at -j 2 the twelve took 1 979 s wall, rec12
# 437 s, with the same names and errors.
python3 scripts/score_recordings.py "${sets[@]}" --binary build/bin/drillwave --out "$out" --parallel 2 -j 2 \
    --min-precision "${SCORE_MIN_PRECISION:-0.9}" --min-recall "${SCORE_MIN_RECALL:-0.84}" --strict
