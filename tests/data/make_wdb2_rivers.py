#!/usr/bin/python3
"""Real river centrelines for the repair tests: WDB II rivers of GSHHG as `gmt coast` gives them.

    gmt coast -R<region> -Ia -M -Df | tests/data/make_wdb2_rivers.py OUT.geojson [--messy]

Each multi-segment record becomes one LineString feature (FID = its index in gmt's output,
from 1), lon/lat WGS 84, vertices exactly as gmt wrote them. --messy keeps only the
segments that are not simple (GEOS IsSimple through OGR): the lines a run meets first.
Needs Debian's gmt, gmt-gshhg and python3-gdal (not in scripts/setup.sh: only this script uses them).
"""
import json
import sys

from osgeo import ogr


def segments(stream):
    current = None
    for line in stream:
        if line.startswith(">"):
            current = []
            yield current
        elif line.strip():
            x, y = line.split()[:2]
            current.append([float(x), float(y)])


def main():
    out, messy = sys.argv[1], "--messy" in sys.argv[2:]
    features = []
    for fid, points in enumerate(list(segments(sys.stdin)), start=1):
        line = ogr.Geometry(ogr.wkbLineString)
        for x, y in points:
            line.AddPoint_2D(x, y)
        if messy and line.IsSimple():
            continue
        features.append({"type": "Feature", "id": fid, "properties": {"segment": fid},
                         "geometry": {"type": "LineString", "coordinates": points}})
    with open(out, "w") as f:
        json.dump({"type": "FeatureCollection", "features": features}, f, separators=(",", ":"))
        f.write("\n")


main()
