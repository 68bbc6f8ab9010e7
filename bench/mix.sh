#!/usr/bin/env bash
# Several exemplars in one feature (docs/synthesis.md, "Several exemplars in one feature"): the
# time per feature of pipelines/mix.yaml as it is (roads: a mix of 3 exemplars with bindings;
# rivers: a free mix of 2 with a switching cost) against the same run with one exemplar per
# class (lanes; cobbles), from report.json's per-feature synthesis seconds. Prints numbers,
# never fails on time. Usage: bench/mix.sh   (env TERRAWEAVE=build/src/terraweave,
# WORK=/tmp/terraweave-mix, THREADS: --threads for both runs)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=$(realpath "${TERRAWEAVE:-build/src/terraweave}")
work=${WORK:-/tmp/terraweave-mix}
threads=()
[ -n "${THREADS:-}" ] && threads=(--threads "$THREADS")
[ -x "$bin" ] || { echo "mix: build $bin first" >&2; exit 1; }
mkdir -p "$work"
single=()
for class in roads rivers; do
  single+=(--set "features.$class.synthesis.choose=seed" --set "features.$class.synthesis.bind=null"
           --set "features.$class.synthesis.switch_cost=null")
done
single+=(--set features.roads.synthesis.exemplar=samples/exemplars/road_lanes_240x64.png
         --set features.rivers.synthesis.exemplar=samples/exemplars/cobble_bed_260x80.png)
"$bin" -q run pipelines/mix.yaml "${threads[@]}" --out "$work/mix"
"$bin" -q run pipelines/mix.yaml "${threads[@]}" --out "$work/single" \
  "${single[@]}"
python3 - "$work/mix/report.json" "$work/single/report.json" <<'PY'
import json, sys
runs = [json.load(open(p)) for p in sys.argv[1:3]]
print(f"{'class':8} {'features':>8} {'pieces':>7} {'single s':>9} {'mix s':>8} {'ms/piece single':>16} "
      f"{'ms/piece mix':>13} {'ratio':>6} {'switches':>8}")
for c_mix, c_one in zip(runs[0]["classes"], runs[1]["classes"]):
    fm = [f for f in c_mix["features"] if "synthesis" in f]
    fo = [f for f in c_one["features"] if "synthesis" in f]
    pieces = sum(f["pieces"] for f in fm)
    seconds = lambda run: sum(t["synthesis"] for t in run["timings"]["synthesis"]
                              if t["class"] == c_mix["name"])
    tm, to = seconds(runs[0]), seconds(runs[1])
    switches = sum(f["synthesis"]["mix"]["switches"] for f in fm if "mix" in f["synthesis"])
    print(f"{c_mix['name']:8} {len(fm):8d} {pieces:7d} {to:9.2f} {tm:8.2f} {1e3 * to / max(pieces, 1):16.1f} "
          f"{1e3 * tm / max(pieces, 1):13.1f} {tm / max(to, 1e-9):6.2f} {switches:8d}")
PY
