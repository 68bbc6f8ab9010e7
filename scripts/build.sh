#!/usr/bin/env bash
# Configures and builds terraweave into build/ (RelWithDebInfo, Ninja). Quiet: the compiler's
# output goes to build/build.log and is shown only when the build fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@" >/dev/null
echo "build: compiling terraweave (log: build/build.log)"
if ! cmake --build build --parallel "$(nproc)" >build/build.log 2>&1; then
  tail -n 60 build/build.log
  echo "build: FAILED (full log: build/build.log)" >&2
  exit 1
fi
