#!/usr/bin/python3
"""Draws each element of samples/ornaments/*.json into samples/ornaments/<name>.png: splines in
black (one grey level per spline), growth points as red ticks along their direction, the origin
as a blue dot. Planar Bézier evaluation only (the terrain version is src/ornament)."""
import json
import math
import pathlib

from osgeo import gdal, ogr

ROOT = pathlib.Path(__file__).resolve().parent.parent / "samples" / "ornaments"
CELL = 180  # pixels per element panel
gdal.UseExceptions()


def cubic(points, per_segment=24):
    out = [points[0]]
    for s in range(0, len(points) - 3, 3):
        p = points[s:s + 4]
        for k in range(1, per_segment + 1):
            t = k / per_segment
            u = 1 - t
            w = (u**3, 3 * u * u * t, 3 * u * t * t, t**3)
            out.append([sum(w[i] * p[i][d] for i in range(4)) for d in (0, 1)])
    return out


def panel(element):
    lines = [(cubic(s["points"]), 255) for s in element["splines"]]
    for g in element.get("growth_points", []):
        a = math.radians(g.get("angle_deg", 0))
        x, y = g["at"]
        lines.append(([[x, y], [x + 0.15 * math.cos(a), y + 0.15 * math.sin(a)]], 1))
    lines.append(([[-0.03, 0], [0.03, 0]], 2))
    lines.append(([[0, -0.03], [0, 0.03]], 2))
    xs = [p[0] for l, _ in lines for p in l]
    ys = [p[1] for l, _ in lines for p in l]
    span = max(max(xs) - min(xs), max(ys) - min(ys)) * 1.2
    cx, cy = (max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2
    ds = gdal.GetDriverByName("MEM").Create("", CELL, CELL, 1, gdal.GDT_Byte)
    ds.SetGeoTransform([cx - span / 2, span / CELL, 0, cy + span / 2, 0, -span / CELL])
    mem = ogr.GetDriverByName("Memory").CreateDataSource("")
    layer = mem.CreateLayer("l")
    layer.CreateField(ogr.FieldDefn("v", ogr.OFTInteger))
    for line, value in lines:
        f = ogr.Feature(layer.GetLayerDefn())
        g = ogr.Geometry(ogr.wkbLineString)
        for x, y in line:
            g.AddPoint_2D(x, y)
        f.SetGeometry(g.Buffer(span / CELL * 1.2))
        f.SetField("v", value)
        layer.CreateFeature(f)
    gdal.RasterizeLayer(ds, [1], layer, options=["ATTRIBUTE=v"])
    return ds.GetRasterBand(1).ReadRaster()


def main():
    colours = {0: (255, 255, 255), 255: (30, 30, 30), 1: (220, 40, 40), 2: (40, 90, 220)}
    for path in sorted(ROOT.glob("*.json")):
        elements = json.loads(path.read_text())["elements"]
        width = CELL * len(elements)
        bands = [bytearray(b"\xff" * (width * CELL)) for _ in range(3)]
        for i, e in enumerate(elements):
            labels = panel(e)
            for row in range(CELL):
                for col in range(CELL):
                    colour = colours[labels[row * CELL + col]]
                    for b in range(3):
                        bands[b][row * width + i * CELL + col] = colour[b]
        out = gdal.GetDriverByName("MEM").Create("", width, CELL, 3, gdal.GDT_Byte)
        for b in range(3):
            out.GetRasterBand(b + 1).WriteRaster(0, 0, width, CELL, bytes(bands[b]))
        gdal.GetDriverByName("PNG").CreateCopy(str(path.with_suffix(".png")), out)
        print(path.with_suffix(".png"))


if __name__ == "__main__":
    main()
