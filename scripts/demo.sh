#!/usr/bin/env bash
# Installs, builds and runs the demo pipeline on samples/; results land in out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/src/terraweave run pipelines/demo.yaml --out out "$@"
