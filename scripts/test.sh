#!/usr/bin/env bash
# Installs, builds and runs the whole GoogleTest suite through ctest.
#   bash scripts/test.sh                      the suite in build/
#   bash scripts/test.sh --sanitize [REGEX]   the suite (or the ctest -R REGEX part of it) built
#                                             with ASan + UBSan in build-asan/; any report fails
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--sanitize" ]; then
  TERRAWEAVE_BUILD_DIR=build-asan bash scripts/build.sh -DTERRAWEAVE_SANITIZE=ON -DTERRAWEAVE_BENCH=OFF
  source scripts/sanitizer/env.sh
  cd build-asan
  ctest --output-on-failure --parallel "$(nproc)" --timeout 600 ${2:+-R "$2"}
  exit
fi
bash scripts/build.sh
cd build
ctest --output-on-failure --parallel "$(nproc)" --timeout 600
