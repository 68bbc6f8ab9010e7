#!/usr/bin/env bash
# Installs, builds and runs the test suite through ctest.
#   bash scripts/test.sh                        the whole suite in build/, then the geo, layers
#                                               and pipeline tests under the sanitizers (CI)
#   bash scripts/test.sh --sanitize [MODULE...] the suite (or only the tests of these modules:
#                                               core geo ribbon raster synth terrain ornament layers
#                                               pipeline) built with ASan + UBSan in build-asan/;
#                                               any sanitizer report fails its test
set -euo pipefail
cd "$(dirname "$0")/.."

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
    -DTERRAWEAVE_SANITIZE=ON -DTERRAWEAVE_BENCH=OFF
  source scripts/sanitizer/env.sh
  (cd build-asan && ctest --output-on-failure --parallel "$(nproc)" --timeout 600 \
    ${labels:+-L "^($labels)\$"})
}

if [ "${1:-}" = "--sanitize" ]; then
  shift
  sanitized_tests "$@"
  exit
fi
bash scripts/build.sh
(cd build && ctest --output-on-failure --parallel "$(nproc)" --timeout 600)
# The whole suite under the sanitizers does not fit CI's 20 minutes on 2 cores
# (docs/robustness.md); the modules that read files and write rasters do. The pipeline tests
# under the sanitizers: `bash scripts/test.sh --sanitize pipeline`.
sanitized_tests geo layers
