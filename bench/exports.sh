#!/usr/bin/env bash
# Engine exports (docs/exports.md "Measured"): wall time, peak RSS (GNU time) and the size of
# what `terraweave export` writes, per engine, for the demo run (untiled, 1200^2) and for a
# generated 8192^2 world run tiled (2048; heights, splat and the two roads of
# pipelines/generated_lines.geojson: the export reads layers, whatever made them). Unreal and
# Unity both as one heightmap (--tile-size 0) and as World Partition / Terrain Tools tiles
# (the tiled run's default); Godot's HTerrain and Terrain3D (the world's cells as they are).
# Prints numbers, never fails on time. Usage: bench/exports.sh [demo] [8192]   (env TERRAWEAVE=build/src/terraweave,
# WORK=/tmp/terraweave-exports)
set -uo pipefail
cd "$(dirname "$0")/.."
bin=$(realpath "${TERRAWEAVE:-build/src/terraweave}")
work=${WORK:-/tmp/terraweave-exports}
worlds=("$@")
[ ${#worlds[@]} -gt 0 ] || worlds=(demo 8192)
[ -x "$bin" ] || { echo "exports: build $bin first" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "exports: needs GNU time (scripts/setup.sh installs it)" >&2; exit 1; }
mkdir -p "$work"

rows=()
measure() {  # world label -- command...
  local world=$1 label=$2
  shift 3
  local log="$work/$world-$label.time" out="$work/$world-$label"
  rm -rf "$out"
  if /usr/bin/time -v "$@" --out "$out" >"$log.out" 2>"$log"; then status=ok; else status=FAILED; fi
  local rss_kb wall bytes files
  rss_kb=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$log")
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' "$log" |
    awk -F: '{ s = 0; for (i = 1; i <= NF; i++) s = s * 60 + $i; print s }')
  bytes=$(du -sbL "$out" 2>/dev/null | awk '{print $1}')
  files=$(find -L "$out" -type f -not -path '*/.terraweave/*' 2>/dev/null | wc -l)
  rows+=("$world $label ${wall:-0} $(( ${rss_kb:-0} / 1024 )) $(( ${bytes:-0} / 1048576 )) $files $status")
  echo "exports: $world $label: ${wall:-?} s, $(( ${rss_kb:-0} / 1024 )) MiB, $files files, $status" >&2
}

for world in "${worlds[@]}"; do
  run="$work/run-$world"
  if [ ! -f "$run/report.json" ]; then
    if [ "$world" = demo ]; then
      "$bin" -q run pipelines/demo.yaml --out "$run" --set output.preview=false || exit 1
    else
      cat >"$work/world-$world.yaml" <<YAML
version: 1
seed: 7
generate: { width: $world, height: $world, pixel_size: 2, relief: 150, crs: "EPSG:32631", origin: [500000, 5000000] }
output: { dir: out, exr: false, preview: false, tiles: { size: 2048, overlap: 0 } }
features:
  roads: { source: $PWD/pipelines/generated_lines.geojson, where: "kind = 'road'", kind: road, width: 6 }
YAML
      "$bin" -q run "$work/world-$world.yaml" --out "$run" || exit 1
    fi
  fi
  for engine in unreal unity; do
    measure "$world" "$engine-whole" -- "$bin" -q export "$run" --to "$engine" --tile-size 0
    [ "$world" = demo ] || measure "$world" "$engine-tiles" -- "$bin" -q export "$run" --to "$engine"
  done
  measure "$world" godot -- "$bin" -q export "$run" --to godot
  measure "$world" terrain3d -- "$bin" -q export "$run" --to terrain3d
done

printf '\n%-6s %-13s %8s %9s %8s %6s %s\n' world export wall_s peak_MiB MiB files status
for row in "${rows[@]}"; do
  read -r world label wall rss mib files status <<<"$row"
  printf '%-6s %-13s %8s %9s %8s %6s %s\n' "$world" "$label" "$wall" "$rss" "$mib" "$files" "$status"
done
