# Sourced by bench/nightly.sh and bench/render_tile.sh: the generated world both measure.
# lanes_world BIN ROOT SIZE PIXEL TILE STRIDE, in the current folder: terraweave make-world
# (SIZE^2 cells of PIXEL m, roads and rivers, tiles of TILE + 16 overlap; its one-line summary
# on stdout), then world.yaml's roads split by FID: every STRIDE-th one in a class `lanes` of
# its own with lane markings synthesized (ROOT's road_lanes exemplar), the others left plain.
lanes_world() {
  local bin=$1 root=$2 size=$3 pixel=$4 tile=$5 stride=$6
  "$bin" -q make-world --size "$size" --pixel "$pixel" --tile "$tile" --overlap 16 --out . ||
    return 1
  python3 - "$stride" "$root/samples/exemplars/road_lanes_240x64.png" <<'PY' || return 1
import sys
stride, exemplar = sys.argv[1], sys.argv[2]
text = open("world.yaml").read()
text = text.replace("precedence: [rivers, roads]", "precedence: [rivers, lanes, roads]")
roads = text[text.index("  roads:"):]
lanes = roads.replace("  roads:", "  lanes:", 1) + (
    f'    where: "fid % {stride} = 0"\n'
    f"    synthesis: {{ exemplar: {exemplar}, width: 10, scale: 4, delta: 14,\n"
    "                 channels: { alpha: splat.road_marking, height: height } }\n")
text = text.replace(roads, roads + f'    where: "fid % {stride} <> 0"\n' + lanes)
open("world.yaml", "w").write(text)
PY
}
