#!/usr/bin/env bash
# Scaling of a generated world (terraweave make-world: generated heights, roads and rivers at
# the demo's density, about 1 km of features per km^2) from 8192^2 to 32768^2 cells: wall time
# and peak RSS (GNU time's "Maximum resident set size") of
#   plan     terraweave validate world.yaml   (ingest, ribbons, terrain plan; writes nothing)
#   tiled    terraweave run world.yaml        (output.tiles: TILE, overlap OVERLAP)
#   untiled  terraweave run world_untiled.yaml (one window; at UNTILED_SIZES only)
# (tiled needs run_pipeline's tile loop, plan_world + render_tile: docs/tiles.md; a run that
# ignores output.tiles renders one window, and its peak RSS then grows with the world.)
# Prints numbers and ratios, never fails on time. Usage:
#   bench/bigworld.sh [SIZES...]   (default 8192 16384 32768; env TILE, OVERLAP, UNTILED_SIZES,
#                                   TERRAWEAVE=build/src/terraweave, WORK=/tmp/terraweave-bigworld,
#                                   SKIP_PLAN=1 to skip the separate plan measurement)
# Layers are deleted after each run; WORK/SIZE/MODE-report.json and the output bytes are kept.
set -uo pipefail
cd "$(dirname "$0")/.."
bin=${TERRAWEAVE:-build/src/terraweave}
work=${WORK:-/tmp/terraweave-bigworld}
tile=${TILE:-2048}
overlap=${OVERLAP:-64}
untiled_sizes=${UNTILED_SIZES:-8192}
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(8192 16384 32768)
[ -x "$bin" ] || { echo "bigworld: build $bin first" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "bigworld: needs GNU time (scripts/setup.sh installs it)" >&2; exit 1; }

rows=()
measure() {  # size mode km -- command...
  local size=$1 mode=$2 km=$3
  shift 4
  local log="$work/$size/$mode.time"
  if /usr/bin/time -v "$@" >"$work/$size/$mode.log" 2>"$log"; then status=ok; else status=FAILED; fi
  local rss_kb wall
  rss_kb=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$log")
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' "$log" |
    awk -F: '{ s = 0; for (i = 1; i <= NF; i++) s = s * 60 + $i; print s }')
  rows+=("$size $mode $km ${wall:-0} ${rss_kb:-0} $status")
  echo "bigworld: $size^2 $mode: ${wall:-?} s, $(( ${rss_kb:-0} / 1024 )) MiB peak RSS, $status" >&2
}

keep_report() {  # size mode out: report.json, output bytes and per-tile seconds
  local size=$1 mode=$2 out=$3
  cp -L "$out/report.json" "$work/$size/$mode-report.json" 2>/dev/null
  local bytes
  bytes=$(du -sbL "$out" | awk '{print $1}')
  python3 - "$work/$size/$mode-report.json" "$bytes" <<'PY' >&2
import json, sys
bytes_ = int(sys.argv[2])
try:
    tiles = json.load(open(sys.argv[1])).get("timings", {}).get("tiles", [])
except (OSError, ValueError):
    tiles = []
secs = sorted(t.get("seconds", 0) for t in tiles)
line = f"bigworld: output {bytes_ / 1e9:.2f} GB"
if secs:
    line += (f", {len(secs)} tiles: {sum(secs) / len(secs):.2f} s mean, "
             f"{secs[len(secs) // 2]:.2f} s median, {secs[0]:.2f}-{secs[-1]:.2f} s")
print(line)
PY
}

for size in "${sizes[@]}"; do
  mkdir -p "$work/$size"
  summary=$("$bin" -q make-world --size "$size" --tile "$tile" --overlap "$overlap" \
    --out "$work/$size") || exit 1
  km=$(echo "$summary" | awk '{print $3 + $7}')
  echo "bigworld: $size^2: $summary" >&2
  [ -n "${SKIP_PLAN:-}" ] || measure "$size" plan "$km" -- "$bin" -q validate "$work/$size/world.yaml"
  measure "$size" tiled "$km" -- "$bin" -q run "$work/$size/world.yaml" --out "$work/$size/out"
  keep_report "$size" tiled "$work/$size/out"
  rm -rf "$work/$size/out"
  for u in $untiled_sizes; do
    if [ "$u" = "$size" ]; then
      measure "$size" untiled "$km" -- "$bin" -q run "$work/$size/world_untiled.yaml" \
        --out "$work/$size/out_untiled"
      keep_report "$size" untiled "$work/$size/out_untiled"
      rm -rf "$work/$size/out_untiled"
    fi
  done
done

printf '\n%-7s %-8s %8s %8s %9s %10s %10s %9s %s\n' size mode Mpx km wall_s peak_MiB s_per_Mpx MiB_ratio status
base_rss=""
for row in "${rows[@]}"; do
  read -r size mode km wall rss status <<<"$row"
  awk -v size="$size" -v mode="$mode" -v km="$km" -v wall="$wall" -v rss="$rss" \
    -v status="$status" -v base="${base_rss:-$rss}" 'BEGIN {
      mpx = size * size / 1e6
      printf "%-7d %-8s %8.0f %8.0f %9.1f %10.0f %10.4f %9.2f %s\n", size, mode, mpx, km, wall,
        rss / 1024, wall / mpx, rss / base, status }'
  [ -n "$base_rss" ] || base_rss=$rss
done
echo "(MiB_ratio: peak RSS over the first row's)"
