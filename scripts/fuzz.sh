#!/usr/bin/env bash
# Builds the libFuzzer targets in fuzz/ with clang into build-fuzz/ and runs each for a bounded
# time: bash scripts/fuzz.sh [SECONDS_PER_TARGET (default 60)] [TARGET...].
# Each target starts from fuzz/corpus/<target>/ (kept in git) and grows build-fuzz/corpus/<target>/;
# a finding (crash, sanitizer report, leak, uncaught exception, broken promise, timeout over 10 s,
# more than 2 GiB) lands in build-fuzz/findings/<target>/. Exits non-zero when any target found
# something. A tw::Error is the expected answer to bad input, never a finding.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
all_targets=(pipeline_parser set_override placements_loader vector_ingest element_set sketch_loader
  plan_object cache_entry network_exemplar)
[ $# -gt 0 ] && targets=("$@") || targets=("${all_targets[@]}")

# clang and its runtime (libFuzzer, ASan, UBSan): needed only here, so not in setup.sh's list.
bash scripts/setup.sh clang libclang-rt-dev

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DTERRAWEAVE_FUZZ=ON -DTERRAWEAVE_TESTS=OFF -DTERRAWEAVE_BENCH=OFF "${launcher[@]}" >/dev/null
echo "fuzz: building ${targets[*]} (log: build-fuzz/build.log)"
if ! cmake --build build-fuzz --parallel "$(nproc)" --target "${targets[@]/#/fuzz_}" \
  >build-fuzz/build.log 2>&1; then
  tail -n 40 build-fuzz/build.log
  echo "fuzz: build FAILED (full log: build-fuzz/build.log)" >&2
  exit 1
fi

source scripts/sanitizer/env.sh
# libFuzzer reports leaks itself, per input.
export ASAN_OPTIONS="$ASAN_OPTIONS:detect_stack_use_after_return=0"

dictionary_of() {
  case "$1" in
    pipeline_parser | set_override) echo fuzz/dict/pipeline.dict ;;
    placements_loader) echo fuzz/dict/placements.dict ;;
    vector_ingest | sketch_loader) echo fuzz/dict/geojson.dict ;;
    network_exemplar) echo fuzz/dict/network.dict ;;
  esac
}

status=0
printf '%-18s %12s %8s %9s  %s\n' target executions exec/s findings log
for t in "${targets[@]}"; do
  # A finding of an earlier run moves to findings.old/, so the count below is this run's.
  if [ -d "build-fuzz/findings/$t" ]; then
    mkdir -p build-fuzz/findings.old
    rm -rf "build-fuzz/findings.old/$t"
    mv "build-fuzz/findings/$t" "build-fuzz/findings.old/$t"
  fi
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/findings/$t"
  log="build-fuzz/$t.log"
  rc=0
  dictionary=()
  [ -n "$(dictionary_of "$t")" ] && dictionary=(-dict="$(dictionary_of "$t")")
  "build-fuzz/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 "${dictionary[@]}" \
    -artifact_prefix="build-fuzz/findings/$t/" "build-fuzz/corpus/$t" "fuzz/corpus/$t" \
    >"$log" 2>&1 || rc=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)
  findings=$(find "build-fuzz/findings/$t" -type f | wc -l)
  printf '%-18s %12s %8s %9s  %s\n' "$t" "${runs:-?}" "${rate:-?}" "$findings" "$log"
  if [ "$rc" -ne 0 ] || [ "$findings" -gt 0 ]; then
    status=1
    grep -m 3 -E 'ERROR: |runtime error|broken promise|deadly signal|uncaught exception' "$log" || true
    find "build-fuzz/findings/$t" -type f | sed 's/^/  finding: /'
  fi
done
exit "$status"
