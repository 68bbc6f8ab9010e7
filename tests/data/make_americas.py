#!/usr/bin/python3
"""The Americas as one continent polygon, and the Seychelles, from GMT's DCW country polygons.

    gmt coast -E=NA,=SA,SC -M -R-180/180/-60/85 | tests/data/make_americas.py OUT.geojson

Every ring gmt writes (one per country part) becomes a polygon; those over 0.01 square degrees,
simplified to 0.01 degrees and grown by 0.05 degrees (so that neighbours whose borders do not
meet exactly merge), are unioned (GEOS through OGR), the outer ring of the largest polygon of the union (the mainland from Alaska to
Tierra del Fuego, lakes left out) and of those between 40 and 70 degrees east (the Seychelles) are simplified
to 0.05 degrees and written as one MultiPolygon, FID 1 (a "land" layer's feature). Lon/lat
WGS 84; the coast lies up to 0.05 + 0.05 degrees off the real one. Needs Debian's gmt and python3-gdal.
"""
import json
import sys

from osgeo import ogr


def rings(stream):
    current = None
    for line in stream:
        if line.startswith(">"):
            if current:
                yield current
            current = []
        elif line.strip():
            x, y = line.split()[:2]
            current.append((float(x), float(y)))
    if current:
        yield current


def main():
    out = sys.argv[1]
    parts = ogr.Geometry(ogr.wkbMultiPolygon)
    for points in rings(sys.stdin):
        ring = ogr.Geometry(ogr.wkbLinearRing)
        for x, y in points:
            ring.AddPoint_2D(x, y)
        ring.CloseRings()
        polygon = ogr.Geometry(ogr.wkbPolygon)
        polygon.AddGeometry(ring)
        if polygon.GetArea() > 0.01:
            parts.AddGeometry(polygon.SimplifyPreserveTopology(0.01).Buffer(0.05, 2))
    union = parts.UnionCascaded()
    polygons = [union.GetGeometryRef(i) for i in range(union.GetGeometryCount())]
    largest = max(polygons, key=lambda g: g.GetArea())
    kept = [largest] + [g for g in polygons if 40 < g.Centroid().GetX() < 70]
    coordinates = []
    for polygon in kept:
        shell = ogr.Geometry(ogr.wkbPolygon)
        shell.AddGeometry(polygon.GetGeometryRef(0))  # no lakes
        simplified = shell.SimplifyPreserveTopology(0.05)
        ring = simplified.GetGeometryRef(0).GetPoints()
        coordinates.append([[[round(x, 5), round(y, 5)] for x, y, *_ in ring]])
    with open(out, "w") as f:
        json.dump({"type": "FeatureCollection",
                   "features": [{"type": "Feature", "id": 1, "properties": {"name": "Americas and Seychelles"},
                                 "geometry": {"type": "MultiPolygon", "coordinates": coordinates}}]},
                  f, separators=(",", ":"))
        f.write("\n")


main()
