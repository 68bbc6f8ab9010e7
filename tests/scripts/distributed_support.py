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
# A world with syntheses (tests/pipeline/cache_world.cpp's): a generated 640 m terrain with five
# cobbled roads (R1 and R2 cross, R4 runs beside R1's east end, R3 and R5 far from the rest), in
# 3 x 3 tiles of 64 pixels with 4 of overlap. Synthesis order is FID order.
ROADS_PIPELINE = """version: 1
seed: 5
generate: { width: 160, height: 160, pixel_size: 4, relief: 40, origin: [500000, 5000640] }
synthesis_resolution: 1
output: { tiles: { size: 64, overlap: 4 } }
avoidance: { max_distance: 24 }      # a halo of 7 pixels: a changed road reaches a few tiles
features:
  roads:
    source: roads.gpkg
    layer: roads
    kind: road
    width: 6
    profile: { shoulder_width: 2, falloff: 10 }
    synthesis: { exemplar: cobble.png, width: 8, scale: 5, delta: 8 }
"""
ROADS = [[(50, 300), (590, 300)], [(320, 50), (320, 590)], [(50, 450), (250, 450)],
         [(450, 318), (590, 318)], [(50, 100), (250, 100)]]
# R1 with its east end moved 10 m north: R1 and R2 (their crossing moved) are resynthesized; R4's
# key changes too (R1's new canvas overlaps it) but its mask does not: a task, which the finer
# check reuses (docs/cache.md); R3 and R5 are reused (cache_test.cpp works these sets out).
ROADS_R1_MOVED = [[(50, 300), (590, 310)]] + ROADS[1:]
REBUILT_WHEN_R1_MOVED = {1, 2}


def write_roads_world(folder, roads=ROADS):
    """pipeline.yaml, roads.gpkg (FID 1..5) and the cropped cobble exemplar in `folder`;
    returns the pipeline's path."""
    from osgeo import ogr, osr
    ogr.UseExceptions()
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "roads.gpkg")
    if os.path.exists(path):
        os.remove(path)
    source = ogr.GetDriverByName("GPKG").CreateDataSource(path)
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32631)
    layer = source.CreateLayer("roads", srs, ogr.wkbLineString)
    layer.CreateField(ogr.FieldDefn("width", ogr.OFTReal))
    for line in roads:
        feature = ogr.Feature(layer.GetLayerDefn())
        feature.SetField("width", 6.0)
        wkt = ", ".join(f"{500000 + x} {5000000 + y}" for x, y in line)
        feature.SetGeometry(ogr.CreateGeometryFromWkt(f"LINESTRING ({wkt})"))
        layer.CreateFeature(feature)
    source = None
    exemplars = os.path.join(SOURCE_DIR, "samples", "exemplars")
    for name, target, driver in (("cobble_edging_200x56.png", "cobble.png", "PNG"),
                                 ("cobble_edging_200x56_height.tif", "cobble_height.tif", "GTiff")):
        if not os.path.exists(os.path.join(folder, target)):
            gdal.Translate(os.path.join(folder, target), os.path.join(exemplars, name),
                           srcWin=[0, 0, 60, 56], format=driver)
    pipeline = os.path.join(folder, "pipeline.yaml")
    with open(pipeline, "w") as f:
        f.write(ROADS_PIPELINE)
    return pipeline


def cache_statuses(folder):
    """report.json's cache statuses: {feature FID: (status, why)} and {tile index: (...)}."""
    report = json.load(open(os.path.join(folder, "report.json")))
    features = {f["fid"]: (f["cache"]["status"], f["cache"]["why"])
                for c in report["classes"] for f in c["features"] if "cache" in f}
    tiles = {t["index"]: (t["cache"]["status"], t["cache"]["why"])
             for t in report["tiles"]["tiles"] if "cache" in t}
    return features, tiles


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


def without_timings(value, ignore=frozenset()):
    """`value` without its timings (and the keys in `ignore`), at any depth."""
    if isinstance(value, dict):
        return {k: without_timings(v, ignore) for k, v in value.items()
                if k not in TIMING_KEYS and k not in ignore}
    if isinstance(value, list):
        return [without_timings(v, ignore) for v in value]
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


def same_outputs(expected, actual, ignore=frozenset()):
    """Every file of `expected` exists in `actual` with the same bytes (report.json: the same
    values but timings and the keys in `ignore`); and nothing more."""
    names = outputs(expected)
    check(names == outputs(actual), f"different files:\n{names}\n{outputs(actual)}")
    check(any(n.startswith("tiles" + os.sep) for n in names), f"no tiles in {expected}")
    for name in names:
        a, b = os.path.join(expected, name), os.path.join(actual, name)
        if name == "report.json":
            ra = without_timings(json.load(open(a)), ignore)
            rb = without_timings(json.load(open(b)), ignore)
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
