#!/usr/bin/env bash
# One `terraweave render-tile` of a planned generated world (issue #23 item 4, docs/performance.md,
# "The plan's objects as bytes"): terraweave make-world (SIZE^2 cells of PIXEL m, tiles of TILE
# + 16 overlap) with every STRIDE-th road in a class of its own with lane markings synthesized
# (bench/nightly.sh's world), planned once (`terraweave plan`), then tile TILE_INDEX rendered
# RUNS times. Prints each run's wall time, CPU seconds (user + system) and peak RSS, and their
# ranges; with BASELINE=path/to/another/terraweave, that program plans its own copy and runs
# interleaved with this one (before/after on the same load). With PERF=1 (and perf installed),
# records one run of each (`perf record --call-graph dwarf`) into WORK/perf.<name>.data. With
# SPLIT=N (root, perf with uprobes), N more runs of each under `perf record` with uprobes on
# TileCache::render_or_reuse's entry and return and the process's exec and exit: each prints the
# wall time before, inside and after the tile, the share of the wall outside it, and the share of
# the CPU samples (every thread, 2 kHz) outside it (docs/performance.md, "render-tile").
# Never fails on time. Usage:
#   bench/render_tile.sh   (env SIZE=4096 PIXEL=4 TILE=1024 STRIDE=8 TILE_INDEX=5 RUNS=5
#                           TERRAWEAVE=build/src/terraweave BASELINE= PERF=0 SPLIT=0
#                           WORK=/tmp/terraweave-render-tile)
set -uo pipefail
cd "$(dirname "$0")/.."
root=$PWD
source bench/lib/lanes_world.sh
bin=$(realpath "${TERRAWEAVE:-build/src/terraweave}")
work=${WORK:-/tmp/terraweave-render-tile}
size=${SIZE:-4096}
pixel=${PIXEL:-4}
tile=${TILE:-1024}
stride=${STRIDE:-8}
index=${TILE_INDEX:-5}
runs=${RUNS:-5}
[ -x "$bin" ] || { echo "render_tile: build $bin first" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "render_tile: needs GNU time (scripts/setup.sh installs it)" >&2; exit 1; }
# The image module beside the build tree's program (exemplars are images).
export TERRAWEAVE_IMAGE_MODULE=${TERRAWEAVE_IMAGE_MODULE:-$(dirname "$bin")/libterraweave_image.so}
rm -rf "$work" && mkdir -p "$work/world" || exit 1

cd "$work/world" || exit 1
lanes_world "$bin" "$root" "$size" "$pixel" "$tile" "$stride" >&2 || exit 1

names=(this)
programs=("$bin")
if [ -n "${BASELINE:-}" ]; then
  names+=(baseline)
  programs+=("$(realpath "$BASELINE")")
fi
for i in "${!names[@]}"; do
  mkdir -p "$work/${names[$i]}" && cp world.yaml world.gpkg "$work/${names[$i]}/" || exit 1
  (cd "$work/${names[$i]}" && "${programs[$i]}" -q plan world.yaml >plan.log 2>&1) ||
    { echo "render_tile: ${names[$i]}: plan failed (see $work/${names[$i]}/plan.log)" >&2; exit 1; }
done

for run in $(seq "$runs"); do
  for i in "${!names[@]}"; do
    (cd "$work/${names[$i]}" &&
      /usr/bin/time -f "${names[$i]} %e %U %S %M" -a -o ../times.txt \
        "${programs[$i]}" -q render-tile out --tile "$index" >/dev/null) ||
      { echo "render_tile: ${names[$i]}: render-tile failed" >&2; exit 1; }
  done
done
if [ "${PERF:-0}" = 1 ] && command -v perf >/dev/null; then
  for i in "${!names[@]}"; do
    (cd "$work/${names[$i]}" && perf record -q -g --call-graph dwarf -F 2000 \
      -o "$work/perf.${names[$i]}.data" "${programs[$i]}" -q render-tile out --tile "$index" \
      >/dev/null 2>&1)
  done
fi
if [ "${SPLIT:-0}" -gt 0 ] && command -v perf >/dev/null; then
  for i in "${!names[@]}"; do
    symbol=$(nm "${programs[$i]}" | awk '/TileCache15render_or_reuse/ {print $3; exit}')
    perf probe -q -d "tw_${names[$i]}:*" 2>/dev/null
    perf probe -q -x "${programs[$i]}" -a "tw_${names[$i]}:enter_${names[$i]}=$symbol" &&
      perf probe -q -x "${programs[$i]}" --no-demangle \
        -a "tw_${names[$i]}:leave_${names[$i]}=$symbol%return" ||
      { echo "render_tile: SPLIT needs uprobes (root)" >&2; exit 1; }
  done
  for run in $(seq "$SPLIT"); do
    for i in "${!names[@]}"; do
      (cd "$work/${names[$i]}" && perf record -q -F 2000 -o "$work/split.data" -e cpu-clock \
        -e "tw_${names[$i]}:enter_${names[$i]}" -e "tw_${names[$i]}:leave_${names[$i]}__return" \
        -e sched:sched_process_exec -e sched:sched_process_exit \
        "${programs[$i]}" -q render-tile out --tile "$index" >/dev/null 2>&1)
      perf script -i "$work/split.data" -F pid,tid,time,event 2>/dev/null |
        python3 -c '
import sys
events = [(float(t.rstrip(":")), e.rstrip(":"), who) for who, t, e, *_ in map(str.split, sys.stdin)]
main = events[0][2].split("/")[0] + "/" + events[0][2].split("/")[0]
start = next(t for t, e, _ in events if "exec" in e)
end = max(t for t, e, who in events if "exit" in e and who == main)
enter = next(t for t, e, _ in events if ":enter_" in e)
leave = next(t for t, e, _ in events if ":leave_" in e)
cpu = [t for t, e, _ in events if e == "cpu-clock"]
outside = sum(1 for t in cpu if not enter <= t <= leave)
print(f"  {sys.argv[1]:<9} split    wall {1e3 * (end - start):6.1f} ms: before the tile {1e3 * (enter - start):5.1f},"
      f" tile {1e3 * (leave - enter):6.1f}, after {1e3 * (end - leave):5.1f}; outside the tile"
      f" {100 * (1 - (leave - enter) / (end - start)):4.1f} % of the wall, {100 * outside / len(cpu):4.1f} %"
      f" of {len(cpu)} CPU samples")' "${names[$i]}" >>"$work/split.txt"
    done
  done
  for i in "${!names[@]}"; do perf probe -q -d "tw_${names[$i]}:*" 2>/dev/null; done
fi
echo "render_tile: ${size}^2 cells of $pixel m, tile $index of ${tile}^2 + 16, $runs runs, load $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$work/times.txt" <<'PY'
import collections, sys
runs = collections.defaultdict(list)
for line in open(sys.argv[1]):
    name, wall, user, system, rss = line.split()
    runs[name].append((float(wall), float(user) + float(system), int(rss) / 1024))
for name, values in runs.items():
    for column, unit, k in (("wall", "s", 0), ("CPU", "s", 1), ("peak RSS", "MB", 2)):
        v = sorted(x[k] for x in values)
        print(f"  {name:<9} {column:<9} {v[0]:8.2f} - {v[-1]:8.2f} {unit} (median {v[len(v) // 2]:.2f})")
PY
[ -f "$work/split.txt" ] && sort -s -k1,1 "$work/split.txt"
exit 0
