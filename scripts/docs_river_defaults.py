#!/usr/bin/env python3
"""Draws docs/images/river_defaults.png: the WDBII Moselle over Luxembourg's DEM at 30 m cells,
hillshaded (GDAL's hillshade), as drawn with the old max_carve default (5 x depth = 20 m, left)
and today's (2 x depth = 8 m, right), around the point where the bound holds most (issue #21).

  /usr/bin/python3 scripts/docs_river_defaults.py build/src/terraweave docs/images/river_defaults.png
"""
import json
import subprocess
import sys
import tempfile

import numpy as np
from osgeo import gdal

gdal.UseExceptions()
binary, picture = sys.argv[1], sys.argv[2]
HALF = 2500.0  # metres either side of the worst point


def run(out, extra):
    subprocess.run([binary, "-q", "run", "pipelines/luxembourg.yaml", "--set", "resolution=30",
                    "--set", "features.roads=null", "--out", out] + extra, check=True)


def shade(height_tif, centre, tmp):
    x, y = centre
    crop = gdal.Translate(f"{tmp}/crop.tif", height_tif,
                          projWin=[x - HALF, y + HALF, x + HALF, y - HALF])
    crop = None
    shaded = gdal.DEMProcessing(f"{tmp}/shade.tif", f"{tmp}/crop.tif", "hillshade",
                                zFactor=3, azimuth=315, altitude=45, computeEdges=True)
    return shaded.ReadAsArray().astype(np.uint8)


with tempfile.TemporaryDirectory() as tmp:
    run(f"{tmp}/old", ["--set", "features.rivers.profile.max_carve=20"])
    run(f"{tmp}/new", [])
    report = json.load(open(f"{tmp}/new/report.json"))
    held = [w for w in report["warnings"] if w["code"] == "carve_limited"]
    # The worst point of the longest stretch held: "(x X, y Y)" in the message.
    message = max(held, key=lambda w: float(w["message"].split(" over ")[1].split(" m")[0]))
    at = message["message"].split("(x ")[1].split(")")[0]
    centre = (float(at.split(", y ")[0]), float(at.split(", y ")[1]))
    old = shade(f"{tmp}/old/height.tif", centre, tmp)
    new = shade(f"{tmp}/new/height.tif", centre, tmp)
    gap = np.full((old.shape[0], 8), 255, np.uint8)
    both = np.hstack([old, gap, new]).repeat(2, axis=0).repeat(2, axis=1)  # 2x: legible
    mem = gdal.GetDriverByName("MEM").Create("", both.shape[1], both.shape[0], 1, gdal.GDT_Byte)
    mem.GetRasterBand(1).WriteArray(both)
    gdal.GetDriverByName("PNG").CreateCopy(picture, mem)
    print(f"{picture}: {both.shape[1]} x {both.shape[0]}, centre {centre}")
