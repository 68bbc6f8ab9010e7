#!/usr/bin/env python3
"""Writes samples/olinda.osm: a small OpenStreetMap extract in OSM XML (API 0.6) over
samples/dem.tif, drawn by this project with real OSM tagging conventions (docs/osm.md).

Debian ships no OSM extract of a place covered by a DEM in samples/, so the ways are drawn in
the DEM's UTM 25S metres and converted to WGS 84 (OSM's CRS) with gdaltransform:
  - the river of samples/map.gpkg's `rivers` FID 2 (traced from the DEM), simplified to 30 m,
    as waterway=river; FID 3 as waterway=stream;
  - a highway=primary crossing the river at right angles, in three ways as OSM maps a bridge:
    approach, the bridge (bridge=yes, layer=1, 200 m), approach;
  - a highway=secondary through the hill east of the valley: approach, tunnel=yes + layer=-1
    (720 m between its portals), approach;
  - a closed highway=residential loop with a residential spur tagged width=6 m;
  - the crest of map.gpkg's `ridges` FID 2 as natural=ridge; a landuse=forest area.
samples/olinda.osm.pbf is the same data as PBF, converted with osmconvert (Debian osmctools).
Run from the repository root: python3 scripts/make_osm_sample.py (needs gdal-bin, osmctools).
"""
import subprocess
from xml.sax.saxutils import quoteattr

GPKG = "samples/map.gpkg"
OUT = "samples/olinda.osm"
OUT_PBF = "samples/olinda.osm.pbf"


def wkt_points(layer, fid, tolerance):
    sql = f"SELECT AsText(ST_Simplify(geom, {tolerance})) AS g FROM {layer} WHERE fid = {fid}"
    out = subprocess.run(["ogrinfo", "-ro", "-q", GPKG, "-dialect", "sqlite", "-sql", sql],
                         check=True, capture_output=True, text=True).stdout
    text = out[out.index("LINESTRING"):].split("(", 1)[1].split(")", 1)[0]
    return [tuple(float(v) for v in pair.split()) for pair in text.split(",")]


def to_lon_lat(points):
    text = "".join(f"{x} {y}\n" for x, y in points)
    out = subprocess.run(["gdaltransform", "-s_srs", "EPSG:31985", "-t_srs", "EPSG:4326",
                          "-output_xy"], input=text, check=True, capture_output=True,
                         text=True).stdout
    return [tuple(float(v) for v in line.split()) for line in out.splitlines()]


def along(a, b, step):
    """Points from a to b every ~step metres (both ends included)."""
    n = max(1, round(((b[0] - a[0]) ** 2 + (b[1] - a[1]) ** 2) ** 0.5 / step))
    return [(a[0] + (b[0] - a[0]) * k / n, a[1] + (b[1] - a[1]) * k / n) for k in range(n + 1)]


class Osm:
    def __init__(self):
        self.nodes = []  # (id, x, y) in UTM
        self.ways = []   # (id, [node ids], {tags})
        self.by_point = {}

    def node(self, p):
        key = (round(p[0], 3), round(p[1], 3))
        if key not in self.by_point:  # ways that meet share the node, as in OSM
            self.by_point[key] = len(self.nodes) + 1
            self.nodes.append((len(self.nodes) + 1, p[0], p[1]))
        return self.by_point[key]

    def way(self, way_id, points, tags, closed=False):
        ids = [self.node(p) for p in points]
        if closed:
            ids.append(ids[0])
        self.ways.append((way_id, ids, tags))

    def write(self, path):
        lon_lat = to_lon_lat([(x, y) for _, x, y in self.nodes])
        lines = ['<?xml version="1.0" encoding="UTF-8"?>',
                 '<osm version="0.6" generator="terraweave scripts/make_osm_sample.py">',
                 '  <!-- Drawn by the terraweave project over samples/dem.tif; not OSM data. -->']
        for (node_id, _, _), (lon, lat) in zip(self.nodes, lon_lat):
            lines.append(f'  <node id="{node_id}" version="1" lat="{lat:.7f}" lon="{lon:.7f}"/>')
        for way_id, ids, tags in self.ways:
            lines.append(f'  <way id="{way_id}" version="1">')
            lines += [f'    <nd ref="{i}"/>' for i in ids]
            lines += [f'    <tag k={quoteattr(k)} v={quoteattr(v)}/>' for k, v in tags.items()]
            lines.append("  </way>")
        lines.append("</osm>")
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join(lines) + "\n")


def main():
    osm = Osm()
    river = wkt_points("rivers", 2, 30)
    osm.way(1001, river, {"waterway": "river", "name": "Valley river"})
    osm.way(1002, wkt_points("rivers", 3, 30), {"waterway": "stream"})

    # The primary road crosses the river segment that contains M at right angles.
    a, b = (291341.08, 9115503.41), (291778.11, 9115175.77)
    assert any(abs(p[0] - a[0]) < 1 and abs(p[1] - a[1]) < 1 for p in river), "river changed"
    m = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
    length = ((b[0] - a[0]) ** 2 + (b[1] - a[1]) ** 2) ** 0.5
    n = ((b[1] - a[1]) / -length, (b[0] - a[0]) / length)  # left normal of the river

    def at(t):
        return (m[0] + n[0] * t, m[1] + n[1] * t)

    primary = {"highway": "primary", "name": "Valley road", "surface": "asphalt"}
    osm.way(2001, along(at(-1100), at(-100), 100), primary)
    osm.way(2002, [at(-100), at(100)], {**primary, "bridge": "yes", "layer": "1"})
    osm.way(2003, along(at(100), at(1100), 100), primary)

    y = 9114776.1
    secondary = {"highway": "secondary", "name": "Hill road"}
    osm.way(3001, along((294761.0, y), (295600.0, y), 100), secondary)
    osm.way(3002, [(295600.0, y), (296320.0, y)], {**secondary, "tunnel": "yes", "layer": "-1"})
    osm.way(3003, along((296320.0, y), (296966.0, y), 100), secondary)

    import math
    centre, radius = (293300.0, 9112000.0), 150.0
    loop = [(centre[0] + radius * math.cos(2 * math.pi * k / 12),
             centre[1] + radius * math.sin(2 * math.pi * k / 12)) for k in range(12)]
    osm.way(4001, loop, {"highway": "residential", "name": "Loop street"}, closed=True)
    osm.way(4002, along(loop[0], (centre[0] + 500.0, centre[1]), 100),
            {"highway": "residential", "width": "6 m"})

    osm.way(5001, wkt_points("ridges", 2, 100), {"natural": "ridge"})
    x0, y0 = 296000.0, 9117600.0
    osm.way(6001, [(x0, y0), (x0 + 400, y0), (x0 + 400, y0 + 400), (x0, y0 + 400)],
            {"landuse": "forest"}, closed=True)
    osm.write(OUT)
    subprocess.run(["osmconvert", OUT, "--out-pbf", f"-o={OUT_PBF}"], check=True)


if __name__ == "__main__":
    main()
