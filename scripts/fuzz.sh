#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan; scripts/sanitized-build.sh, the build sanitize.sh tests) and
# runs each for FUZZ_SECONDS seconds (default 60): the case JSON reader, the --set parser, the CSV reader and the recordings' sidecar reader; every case
# the readers accept is also run briefly (fuzz/short_run.hpp). Fails if any target finds a crash, a sanitizer report,
# an exception other than InputError (or NumericalError from a run), an input taking over 10 s or 2 GB; the input that
# did it is left in build-fuzz/artifacts/. Seeds: json-cases/ and fuzz/corpus/; what the fuzzers add stays in
# build-fuzz/corpus.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-60}
bash scripts/sanitized-build.sh drillwave_fuzz_case drillwave_fuzz_set drillwave_fuzz_csv drillwave_fuzz_sidecar
export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
mkdir -p build-fuzz/artifacts
# Dictionaries: every key and string value of json-cases/ and the sidecar seeds as a JSON string (the case and sidecar
# readers) and as a pointer step "/key" (the --set parser), and the CSV reader's tokens, so that mutations reach the
# readers behind the syntax.
tokens=$(grep -ohE '"[A-Za-z_][A-Za-z0-9_]*"' json-cases/*.json fuzz/corpus/sidecar/*.json | sort -u)
sed 's/"/\\"/g; s/.*/"&"/' <<<"$tokens" >build-fuzz/case.dict
sed 's/"//g; s|.*|"/&"|' <<<"$tokens" >build-fuzz/set.dict
printf '"="\n"[0, 5]"\n"1e308"\n"-1"\n"null"\n' >>build-fuzz/set.dict
printf '"time_s"\n","\n"nan"\n"inf"\n"1e999"\n"-0"\n"\\x0d\\x0a"\n' >build-fuzz/csv.dict
failed=()
for target in case set csv sidecar; do
  case $target in
    case) seeds=(json-cases) max_len=65536 dict=(-dict=build-fuzz/case.dict) ;;
    set) seeds=(fuzz/corpus/set) max_len=4096 dict=(-dict=build-fuzz/set.dict) ;;
    csv) seeds=(fuzz/corpus/csv) max_len=4096 dict=(-dict=build-fuzz/csv.dict) ;;
    sidecar) seeds=(fuzz/corpus/sidecar) max_len=4096 dict=(-dict=build-fuzz/case.dict) ;;
  esac
  mkdir -p build-fuzz/corpus/$target
  echo "fuzz.sh: $target for ${seconds} s"
  if ! ./build-fuzz/bin/drillwave_fuzz_$target -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
       -max_len=$max_len "${dict[@]}" -print_final_stats=1 -artifact_prefix=build-fuzz/artifacts/$target- \
       build-fuzz/corpus/$target "${seeds[@]}" 2>build-fuzz/$target.log; then
    tail -n 60 build-fuzz/$target.log >&2
    failed+=("$target")
  fi
  grep -E "^stat::number_of_executed_units|^#[0-9]+ *DONE" build-fuzz/$target.log || true
done
if ((${#failed[@]})); then
  echo "fuzz.sh: ${failed[*]} failed; inputs in build-fuzz/artifacts/ (replay: build-fuzz/bin/drillwave_fuzz_<target> <file>)" >&2
  exit 1
fi
echo "fuzz.sh: no failures in ${seconds} s per target"
