#!/usr/bin/env bash
# Installs, builds and runs the test suite through ctest.
#   bash scripts/test.sh                        the whole suite in build/ (CI); the last line
#                                               is its summary
#   bash scripts/test.sh --sanitize [MODULE...] the suite (or only the tests of these modules:
#                                               core geo ribbon raster synth terrain ornament network layers
#                                               pipeline) built with ASan + UBSan in build-asan/;
#                                               any sanitizer report fails its test
set -uo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh || exit 1

# Runs ctest in folder $1 with the arguments that follow, its output also kept in $1/ctest.log.
run_ctest() {
  local dir="$1"
  shift
  (cd "$dir" && ctest --output-on-failure --parallel "$(nproc)" \
    --timeout "${TW_CTEST_TIMEOUT:-600}" "$@") 2>&1 |
    tee "$dir/ctest.log"
  return "${PIPESTATUS[0]}"
}

sanitized_tests() {
  local targets="" labels=""
  if [ $# -gt 0 ]; then
    # The CLI only for the pipeline tests (they run it); the other modules build without it.
    for m in "$@"; do [ "$m" = pipeline ] && targets="terraweave"; done
    for m in "$@"; do
      targets+=" test_$m"
      labels+="${labels:+|}$m"
    done
  fi
  TERRAWEAVE_BUILD_DIR=build-asan TERRAWEAVE_TARGETS="$targets" bash scripts/build.sh \
    -DTERRAWEAVE_SANITIZE=ON -DTERRAWEAVE_BENCH=OFF || return 1
  (source scripts/sanitizer/env.sh && TW_CTEST_TIMEOUT=1800 run_ctest build-asan ${labels:+-L "^($labels)\$"})
}

# "N tests failed out of M" of a ctest log (0 0 when ctest printed no summary: a build failure).
counts() {
  local line
  line=$(grep -E "tests passed, [0-9]+ tests? failed out of [0-9]+" "$1" 2>/dev/null | tail -n 1)
  if [ -z "$line" ]; then
    echo "0 0"
  else
    echo "$line" | sed -E 's/.* ([0-9]+) tests? failed out of ([0-9]+).*/\1 \2/'
  fi
}

if [ "${1:-}" = "--sanitize" ]; then
  shift
  sanitized_tests "$@"
  exit
fi
# The normal build and the whole suite: what CI runs. The sanitized modules no longer fit CI's 20
# minutes beside it (docs/robustness.md, "Sanitizers in CI"): `bash scripts/test.sh --sanitize
# [MODULE...]` runs them, before merging a change to code that reads files or writes rasters.
rm -f build/ctest.log
bash scripts/build.sh && run_ctest build
suite_status=$?
read -r suite_failed suite_total < <(counts build/ctest.log)
[ "$suite_status" -ne 0 ] && [ "$suite_total" -eq 0 ] && echo "test.sh: the build failed" >&2
# The plain closing line CI reads: 'N passed, N failed' alone.
echo "test.sh: $((suite_total - suite_failed)) passed, $suite_failed failed"
[ "$suite_status" -eq 0 ]
