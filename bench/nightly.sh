#!/usr/bin/env bash
# The nightly rerun (issue #10, "Benchmarks to report"; docs/cache.md): a generated world
# (terraweave make-world: SIZE^2 cells of PIXEL m, roads and rivers at about 1 km per km^2),
# tiled TILE, with every STRIDE-th road synthesized (lane markings), run clean with --cache,
# then road ROAD moved MOVE m north (ogrinfo SQL on the GeoPackage; MOVE=0: nothing changed)
# and rerun with the same cache. Prints clean and rerun wall time and CPU seconds (user +
# system, of the process), their ratios, tiles rebuilt / total and features resynthesized /
# total (from report.json's cache statuses), and whether the rerun's outputs equal a clean run
# of the moved world (bytes of every tile file). Never fails on time. Usage:
#   bench/nightly.sh   (env SIZE=4096 PIXEL=4 TILE=512 STRIDE=8 ROAD=FID MOVE=12 CHECK=1,
#                       TERRAWEAVE=build/src/terraweave, WORK=/tmp/terraweave-nightly)
# ROAD defaults to STRIDE (a synthesized road); ROAD=1 moves a plain one. REPEAT=N: then moves
# the road another MOVE m and reruns on the same cache N more times (the ratios swing by a point
# with the load: docs/performance.md), printing each; the tiles rebuilt and CHECK are then the
# last rerun's.
set -uo pipefail
cd "$(dirname "$0")/.."
root=$PWD
source bench/lib/lanes_world.sh
bin=$(realpath "${TERRAWEAVE:-build/src/terraweave}")
work=${WORK:-/tmp/terraweave-nightly}
size=${SIZE:-4096}
pixel=${PIXEL:-4}
tile=${TILE:-512}
stride=${STRIDE:-8}
move=${MOVE:-12}
[ -x "$bin" ] || { echo "nightly: build $bin first" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1

summary=$(lanes_world "$bin" "$root" "$size" "$pixel" "$tile" "$stride") || exit 1
echo "nightly: $size^2 cells of $pixel m: $summary" >&2
road=${ROAD:-$stride}  # a synthesized road by default
cp world.gpkg world_clean.gpkg

timed() {  # name -- command: wall seconds into $name.s
  local name=$1
  shift 2
  local start end
  start=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o "$name.cpu" "$@" >"$name.log" 2>&1 ||
    { echo "nightly: $name failed (see $work/$name.log)" >&2; exit 1; }
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f\n", b - a }' >"$name.s"
  awk '{ printf "%.3f\n", $1 + $2 }' "$name.cpu" >"$name.cpus"  # user + system CPU seconds
}

timed clean -- "$bin" -q run world.yaml --cache cache --out out_clean
if [ "$move" != 0 ]; then  # MOVE=0: rerun with nothing changed
  ogrinfo -q world.gpkg -sql \
    "UPDATE roads SET geom = ST_Translate(geom, 0, $move, 0) WHERE fid = $road" >/dev/null || exit 1
fi
timed rerun -- "$bin" -q run world.yaml --cache cache --out out_rerun
for ((i = 1; i <= ${REPEAT:-0}; i++)); do
  ogrinfo -q world.gpkg -sql \
    "UPDATE roads SET geom = ST_Translate(geom, 0, $move, 0) WHERE fid = $road" >/dev/null || exit 1
  timed "repeat$i" -- "$bin" -q run world.yaml --cache cache --out out_rerun_$i
  echo "repeat $i: CPU seconds $(cat "repeat$i.cpus"), ratio to the clean run" \
    "$(awk -v r="$(cat "repeat$i.cpus")" -v c="$(cat clean.cpus)" 'BEGIN { printf "%.3f", r / c }')"
done
if [ "${REPEAT:-0}" -gt 0 ]; then  # the checks below look at the last rerun
  rm -rf out_rerun && mv "out_rerun_${REPEAT}" out_rerun
fi
if [ "${CHECK:-1}" = 1 ]; then
  timed moved_clean -- "$bin" -q run world.yaml --out out_moved
fi

python3 - "$road" "$move" <<'PY'
import filecmp, json, os, sys
road, move = sys.argv[1], sys.argv[2]
clean = float(open("clean.s").read())
rerun = float(open("rerun.s").read())
report = json.load(open("out_rerun/report.json"))
tiles = report["tiles"]["tiles"]
rebuilt_tiles = [t for t in tiles if t.get("cache", {}).get("status") == "rebuilt"]
features = [f for c in report["classes"] for f in c["features"] if "cache" in f and f["cache"]]
rebuilt = [f for f in features if f["cache"]["status"] == "rebuilt"]
whys = {}
for f in rebuilt:
    whys[f["cache"]["why"]] = whys.get(f["cache"]["why"], 0) + 1
print(f"road {road} moved {move} m north")
print(f"clean run (cache cold): {clean:.1f} s")
print(f"rerun (cache warm):     {rerun:.1f} s   ratio {rerun / clean:.3f}")
clean_cpu = float(open("clean.cpus").read())
rerun_cpu = float(open("rerun.cpus").read())
print(f"CPU seconds:            clean {clean_cpu:.1f}, rerun {rerun_cpu:.1f}   ratio {rerun_cpu / clean_cpu:.3f}")
print(f"tiles rebuilt:          {len(rebuilt_tiles)} / {len(tiles)}")
print(f"features resynthesized: {len(rebuilt)} / {len(features)} {whys}")
if os.path.exists("moved_clean.s"):
    same = True
    for dirpath, _, names in os.walk("out_moved/tiles"):
        for name in names:
            a = os.path.join(dirpath, name)
            b = os.path.join("out_rerun/tiles", name)
            same &= os.path.exists(b) and filecmp.cmp(a, b, shallow=False)
    print(f"rerun tiles == clean run of the moved world: {'yes' if same else 'NO'} "
          f"(that clean run: {float(open('moved_clean.s').read()):.1f} s)")
PY
