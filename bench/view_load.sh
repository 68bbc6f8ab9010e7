#!/usr/bin/env bash
# The viewer's load time (issue #12 "Benchmarks to report"; docs/exports.md "Measured"): writes
# the page of a run with `terraweave view`, opens it REPEAT times in headless Chromium (Debian's,
# WebGL through SwiftShader, a fresh profile each time, file:// so nothing is served or fetched)
# and prints the page's size and the time to its first rendered frame: the page's own clock
# (window.__terraweaveReady, performance.now() at the first animation frame after drawing,
# counted from the navigation's start, as logged on its console) and the wall time from
# starting Chromium (that plus the browser's start). Prints numbers, never fails on time.
# Usage: bench/view_load.sh [RUN_DIR]   (default: the demo, run into WORK/run-demo if missing;
#   env TERRAWEAVE=build/src/terraweave, WORK=/tmp/terraweave-exports, REPEAT=3,
#   WINDOW=1280,800, CHROMIUM=chromium)
set -uo pipefail
cd "$(dirname "$0")/.."
bin=$(realpath "${TERRAWEAVE:-build/src/terraweave}")
work=${WORK:-/tmp/terraweave-exports}
repeat=${REPEAT:-3}
window=${WINDOW:-1280,800}
chromium=${CHROMIUM:-chromium}
[ -x "$bin" ] || { echo "view_load: build $bin first" >&2; exit 1; }
command -v "$chromium" >/dev/null || { echo "view_load: needs $chromium (apt install chromium)" >&2; exit 1; }
mkdir -p "$work"
run=${1:-$work/run-demo}
if [ ! -f "$run/report.json" ]; then
  [ $# -eq 0 ] || { echo "view_load: $run is not a finished run" >&2; exit 1; }
  "$bin" -q run pipelines/demo.yaml --out "$run" --set output.preview=false || exit 1
fi

page=$work/view.html
start=$(date +%s.%N)
"$bin" -q view "$run" --out "$page" || exit 1
write_s=$(echo "$start $(date +%s.%N)" | awk '{printf "%.2f", $2 - $1}')
bytes=$(stat -c %s "$page")
echo "view_load: $page: $bytes bytes, written in $write_s s" >&2

frames=() walls=()
for i in $(seq "$repeat"); do
  profile=$(mktemp -d "$work/chromium-XXXXXX")
  log=$profile.log
  t0=$(date +%s%N)
  # Its own process group, so the browser and its helpers end together below.
  setsid "$chromium" --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader \
    --window-size="$window" --user-data-dir="$profile" --no-first-run --enable-logging=stderr \
    --v=0 "file://$(realpath "$page")" 2>"$log" >/dev/null &
  pid=$!
  frame="" wall=""
  for _ in $(seq 1200); do  # 120 s at most
    line=$(grep -m1 -o 'terraweave view: ready in [0-9]* ms' "$log" 2>/dev/null)
    if [ -n "$line" ]; then
      wall=$(( ($(date +%s%N) - t0) / 1000000 ))
      frame=$(echo "$line" | awk '{print $5}')
      break
    fi
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  kill -- -"$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  rm -rf "$profile"
  if [ -z "$frame" ]; then
    echo "view_load: run $i: no frame (log: $log)" >&2
    continue
  fi
  rm -f "$log"
  frames+=("$frame") walls+=("$wall")
  echo "view_load: run $i: first frame at $frame ms (page clock), $wall ms after starting Chromium" >&2
done
[ ${#frames[@]} -gt 0 ] || { echo "view_load: the page never drew a frame" >&2; exit 1; }

median() { printf '%s\n' "$@" | sort -n | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
printf '\n%-10s %12s %10s %15s %14s %s\n' page bytes write_s first_frame_ms from_launch_ms runs
printf '%-10s %12s %10s %15s %14s %s\n' "$(basename "$run")" "$bytes" "$write_s" \
  "$(median "${frames[@]}")" "$(median "${walls[@]}")" "${#frames[@]}"
echo "(medians; first_frame_ms: the page's clock from navigation to its first frame)"
