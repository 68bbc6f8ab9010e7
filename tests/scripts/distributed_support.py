"""Shared by the distributed tests: a small tiled world, and comparison of output folders.

A run's outputs are the same bytes whichever way it ran (terraweave run, plan + render-tile +
finish, Dask, Slurm); report.json differs only in timings, which are left out here.
"""
import json
import os
import subprocess
import sys

import numpy
from osgeo import gdal

gdal.UseExceptions()

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PIPELINE = os.path.join(SOURCE_DIR, "pipelines", "generated.yaml")
# 256 x 256 cells of 16 m (the lines of generated.yaml cross it), 3 x 3 tiles of 96 pixels
# with 8 of overlap: the roads and the river cross several tile borders.
OVERRIDES = ["generate.width=256", "generate.height=256", "generate.pixel_size=16",
             "output.tiles.size=96", "output.tiles.overlap=8"]
TIMING_KEYS = {"timings", "stages", "total_seconds", "seconds", "ingest_seconds", "avoidance_seconds",
               "synthesis_seconds", "render_seconds"}


def set_args(overrides=OVERRIDES):
    args = []
    for o in overrides:
        args += ["--set", o]
    return args


def check(condition, message):
    if not condition:
        sys.exit(f"FAILED: {message}")


def run(command, **kwargs):
    completed = subprocess.run(command, capture_output=True, text=True, **kwargs)
    check(completed.returncode == 0,
          f"{' '.join(command)} exited {completed.returncode}:\n{completed.stdout}{completed.stderr}")
    return completed.stdout


def without_timings(value):
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items() if k not in TIMING_KEYS}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def differences(a, b, path=""):
    """JSON pointers where two values differ, with both values."""
    if isinstance(a, dict) and isinstance(b, dict):
        out = []
        for k in sorted(set(a) | set(b)):
            out += differences(a.get(k), b.get(k), f"{path}/{k}")
        return out
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        out = []
        for i, (x, y) in enumerate(zip(a, b)):
            out += differences(x, y, f"{path}/{i}")
        return out
    return [] if a == b else [(path, a, b)]


def outputs(folder):
    """The user-facing files of an output folder (through its links), relative names."""
    names = []
    for root, dirs, files in os.walk(folder):
        dirs[:] = [d for d in dirs if d != ".terraweave"]
        names += [os.path.relpath(os.path.join(root, f), folder) for f in files]
    return sorted(names)


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def same_outputs(expected, actual):
    """Every file of `expected` exists in `actual` with the same bytes (report.json: the same
    values but timings); and nothing more."""
    names = outputs(expected)
    check(names == outputs(actual), f"different files:\n{names}\n{outputs(actual)}")
    check(any(n.startswith("tiles" + os.sep) for n in names), f"no tiles in {expected}")
    for name in names:
        a, b = os.path.join(expected, name), os.path.join(actual, name)
        if name == "report.json":
            ra = without_timings(json.load(open(a)))
            rb = without_timings(json.load(open(b)))
            ra.pop("pipeline", None), rb.pop("pipeline", None)
            check(ra == rb, "report.json differs beyond timings at " + str(differences(ra, rb)[:5]))
        else:
            check(read_bytes(a) == read_bytes(b), f"{name} differs between {expected} and {actual}")
    return names


def mosaic_equals_untiled(tiled, untiled):
    """Each <layer>.vrt of `tiled` holds the pixels of <layer>.tif of an untiled run."""
    count = 0
    for name in outputs(untiled):
        if not name.endswith(".tif"):
            continue
        vrt = os.path.join(tiled, name[:-4] + ".vrt")
        check(os.path.exists(vrt), f"no mosaic {vrt}")
        a = gdal.Open(os.path.join(untiled, name))
        b = gdal.Open(vrt)
        check((a.RasterXSize, a.RasterYSize, a.RasterCount) ==
              (b.RasterXSize, b.RasterYSize, b.RasterCount), f"{name}: other size or bands")
        check(a.GetGeoTransform() == b.GetGeoTransform(), f"{name}: other geotransform")
        for band in range(1, a.RasterCount + 1):
            pa = a.GetRasterBand(band).ReadAsArray()
            pb = b.GetRasterBand(band).ReadAsArray()
            check(numpy.array_equal(pa, pb, equal_nan=True) and
                  numpy.array_equal(numpy.isnan(pa), numpy.isnan(pb)),
                  f"{name} band {band}: mosaic differs from the untiled layer")
        count += 1
    check(count >= 3, f"only {count} layers compared")


def equals_local_run(local, tiled):
    """`tiled` (a distributed run) holds what `local` (terraweave run) holds: every file byte
    for byte when the local run wrote tiles too; from an untiled run, the same pixels in the
    mosaics and the same report values (the tile list aside)."""
    if os.path.isdir(os.path.join(local, "tiles")):
        same_outputs(local, tiled)
        return
    mosaic_equals_untiled(tiled, local)
    a = without_timings(json.load(open(os.path.join(local, "report.json"))))
    b = without_timings(json.load(open(os.path.join(tiled, "report.json"))))
    b.pop("tiles")
    check(a == b, "report.json differs in " + str([k for k in set(a) | set(b) if a.get(k) != b.get(k)]))
