#!/usr/bin/env bash
# Installs, builds and runs the demo pipeline on samples/; results land in out/. Builds the
# command-line program only (not the tests or benchmarks): minutes, not half an hour.
set -euo pipefail
cd "$(dirname "$0")/.."
TERRAWEAVE_TARGETS=terraweave bash scripts/build.sh
./build/src/terraweave run pipelines/demo.yaml --out out "$@"
