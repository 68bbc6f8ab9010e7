#!/usr/bin/env bash
# Configures and builds terraweave into build/ (RelWithDebInfo, Ninja). Quiet: the compiler's
# output goes to build/build.log and is shown only when the build fails. TERRAWEAVE_BUILD_DIR
# names another folder (scripts/test.sh --sanitize builds into build-asan/), TERRAWEAVE_TARGETS
# (space-separated) the targets to build instead of all. Installs only what building needs
# (scripts/setup.sh --build).
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${TERRAWEAVE_BUILD_DIR:-build}"
targets=()
for t in ${TERRAWEAVE_TARGETS:-}; do targets+=(--target "$t"); done
bash scripts/setup.sh --build
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@" >/dev/null
echo "build: compiling terraweave into $dir (log: $dir/build.log)"
if ! cmake --build "$dir" --parallel "$(nproc)" "${targets[@]}" >"$dir/build.log" 2>&1; then
  tail -n 60 "$dir/build.log"
  echo "build: FAILED (full log: $dir/build.log)" >&2
  exit 1
fi
