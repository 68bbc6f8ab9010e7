#!/usr/bin/env bash
# Installs, builds and runs the test suite through ctest.
#   bash scripts/test.sh                        the geo and layers tests under the sanitizers,
#                                               then the whole suite in build/ (CI); the last
#                                               line is the summary of both
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
  (cd "$dir" && ctest --output-on-failure --parallel "$(nproc)" --timeout 600 "$@") 2>&1 |
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
  (source scripts/sanitizer/env.sh && run_ctest build-asan ${labels:+-L "^($labels)\$"})
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
# The whole suite under the sanitizers does not fit CI's 20 minutes on 2 cores
# (docs/robustness.md); the modules that read files and write rasters do. The pipeline tests
# under the sanitizers: `bash scripts/test.sh --sanitize pipeline`. They run first, so that the
# last lines printed are the whole suite's and the summary of both.
rm -f build-asan/ctest.log build/ctest.log
sanitized_tests geo layers
sanitized_status=$?
bash scripts/build.sh && run_ctest build
suite_status=$?
read -r suite_failed suite_total < <(counts build/ctest.log)
read -r asan_failed asan_total < <(counts build-asan/ctest.log)
total=$((suite_total + asan_total))
failed=$((suite_failed + asan_failed))
[ "$suite_status" -ne 0 ] && [ "$suite_total" -eq 0 ] && echo "test.sh: the build failed" >&2
[ "$sanitized_status" -ne 0 ] && [ "$asan_total" -eq 0 ] &&
  echo "test.sh: the sanitizer build failed" >&2
echo "test.sh: the suite $((suite_total - suite_failed))/$suite_total," \
  "geo and layers under the sanitizers $((asan_total - asan_failed))/$asan_total"
# The plain closing line CI reads: 'N passed, N failed' alone.
echo "test.sh: $((total - failed)) passed, $failed failed"
[ "$suite_status" -eq 0 ] && [ "$sanitized_status" -eq 0 ]
