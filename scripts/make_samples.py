#!/usr/bin/python3
"""Regenerates samples/dem.tif, samples/map.gpkg, samples/dem_wgs84.tif,
samples/lines_wgs84.geojson and the preview docs/images/sample_map.png from data
shipped in Debian packages. Usage: make_samples.py SAMPLES_DIR WDBII_TEXT IMAGES_DIR

Run through scripts/make_samples.sh (which installs the packages and runs GMT);
this helper does the GDAL/OGR/numpy work. Everything is deterministic: no random
numbers, fixed crop windows, fixed drawn coordinates, fixed GeoPackage dates.

Sources (see samples/README.md for licences):
  * Olinda DEM, 90 m, UTM 25S (r-cran-stars: tif/olinda_dem_utm25s.tif).
    WDBII (GSHHG) has no river inside it, so its rivers are traced from the DEM
    itself (priority-flood + D8 flow accumulation): they follow the real valleys.
    Ridges are the same trace on the inverted DEM: they follow the real crests.
  * Luxembourg elevation, 30 arc-seconds, EPSG:4326 (r-cran-terra: ex/elev.tif),
    with the real WDBII centreline of the Moselle (gmt coast -Ia -M -Df).
"""
import heapq
import math
import os
import sys

import numpy as np
from osgeo import gdal, ogr, osr
from PIL import Image, ImageDraw

gdal.UseExceptions()
ogr.UseExceptions()
# GeoPackage stamps gpkg_contents.last_change with the current date unless told.
gdal.SetConfigOption("OGR_CURRENT_DATE", "2024-01-01T00:00:00.000Z")

OLINDA = "/usr/lib/R/site-library/stars/tif/olinda_dem_utm25s.tif"
LUXEMBOURG = "/usr/lib/R/site-library/terra/ex/elev.tif"
OLINDA_EPSG = 31985  # SIRGAS 2000 / UTM zone 25S, what the file's proj string describes
# Crop of the Olinda DEM (pixels): 80 x 80 cells of 90 m = 7.2 km across.
CROP_X, CROP_Y, CROP_W, CROP_H = 12, 22, 80, 80
# Luxembourg crop (degrees): the Moselle between Schengen and Grevenmacher.
LUX_BOX = (6.12, 49.44, 6.53, 49.70)  # west, south, east, north

D8 = [(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)]


def priority_flood_receivers(z):
    """D8 receiver of every cell after filling depressions (Barnes et al. 2014):
    cells are visited from the border inwards in increasing height, each one
    draining to the cell it was reached from. Ties go by insertion order."""
    rows, cols = z.shape
    receiver = np.full((rows, cols, 2), -1, dtype=np.int64)
    seen = np.zeros((rows, cols), dtype=bool)
    heap = []
    order = 0
    for r in range(rows):
        for c in range(cols):
            if r in (0, rows - 1) or c in (0, cols - 1):
                heapq.heappush(heap, (float(z[r, c]), order, r, c))
                order += 1
                seen[r, c] = True
    visit_order = []
    while heap:
        h, _, r, c = heapq.heappop(heap)
        visit_order.append((r, c))
        for dr, dc in D8:
            rr, cc = r + dr, c + dc
            if 0 <= rr < rows and 0 <= cc < cols and not seen[rr, cc]:
                seen[rr, cc] = True
                receiver[rr, cc] = (r, c)
                heapq.heappush(heap, (max(float(z[rr, cc]), h), order, rr, cc))
                order += 1
    return receiver, visit_order


def flow_accumulation(receiver, visit_order):
    rows, cols = receiver.shape[:2]
    acc = np.ones((rows, cols), dtype=np.int64)
    for r, c in reversed(visit_order):  # downstream cells were visited first
        rr, cc = receiver[r, c]
        if rr >= 0:
            acc[rr, cc] += acc[r, c]
    return acc


def trace_channels(receiver, acc, threshold, min_cells):
    """Channels = cells with accumulation >= threshold. Each channel starts at a
    head (no channel cell upstream) and runs downstream until it meets a cell
    already traced (a confluence: both lines share that point) or the border."""
    rows, cols = acc.shape
    channel = acc >= threshold
    has_upstream = np.zeros_like(channel)
    for r in range(rows):
        for c in range(cols):
            rr, cc = receiver[r, c]
            if channel[r, c] and rr >= 0:
                has_upstream[rr, cc] = True
    heads = [(r, c) for r in range(rows) for c in range(cols) if channel[r, c] and not has_upstream[r, c]]
    heads.sort(key=lambda rc: (-acc[rc], rc))  # deterministic order
    traced = np.zeros_like(channel)
    lines = []
    # Longest (most upstream area at the outlet) first, so trunks stay whole.
    heads.sort(key=lambda rc: -downstream_length(receiver, rc))
    for r, c in heads:
        cells = [(r, c)]
        while True:
            if traced[r, c] and len(cells) > 1:
                break
            traced[r, c] = True
            rr, cc = receiver[r, c]
            if rr < 0:
                break
            r, c = int(rr), int(cc)
            cells.append((r, c))
        if len(cells) >= min_cells:
            lines.append(cells)
    return lines


def downstream_length(receiver, rc):
    n = 0
    r, c = rc
    while receiver[r, c][0] >= 0:
        r, c = receiver[r, c]
        n += 1
    return n


def chaikin(points, iterations=2):
    """Corner cutting keeps the end points (junctions stay shared)."""
    pts = list(points)
    for _ in range(iterations):
        out = [pts[0]]
        for a, b in zip(pts[:-1], pts[1:]):
            out.append((0.75 * a[0] + 0.25 * b[0], 0.75 * a[1] + 0.25 * b[1]))
            out.append((0.25 * a[0] + 0.75 * b[0], 0.25 * a[1] + 0.75 * b[1]))
        out.append(pts[-1])
        pts = out
    return pts


def cells_to_world(cells, gt):
    return [(gt[0] + (c + 0.5) * gt[1], gt[3] + (r + 0.5) * gt[5]) for r, c in cells]


def smooth_trace(cells, gt, half_window=2):
    """D8 traces step in 45-degree stairs; a moving average (ends pinned, so
    confluences stay shared points) and corner cutting give a plausible centreline."""
    pts = np.array(cells_to_world(cells, gt))
    out = pts.copy()
    for i in range(1, len(pts) - 1):
        k = min(half_window, i, len(pts) - 1 - i)
        out[i] = pts[i - k:i + k + 1].mean(axis=0)
    return chaikin([tuple(p) for p in out], iterations=3)


def smooth_network(traces, gt, snap_distance):
    """Smooths each trace; a trace ending on an earlier one (a confluence) gets its
    end snapped onto a vertex of that smoothed line so the junction stays exact."""
    lines = []
    for cells in traces:
        points = smooth_trace(cells, gt)
        earlier = [p for previous in lines for p in previous]
        if earlier:
            end = np.array(points[-1])
            nearest = min(earlier, key=lambda p: float(np.hypot(*(np.array(p) - end))))
            if float(np.hypot(*(np.array(nearest) - end))) <= snap_distance:
                points[-1] = nearest
        lines.append(points)
    return lines


def make_dem(out_dir):
    src = gdal.Open(OLINDA)
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(OLINDA_EPSG)
    dem_path = os.path.join(out_dir, "dem.tif")
    gdal.Translate(
        dem_path, src, srcWin=[CROP_X, CROP_Y, CROP_W, CROP_H], outputSRS=srs.ExportToWkt(),
        creationOptions=["COMPRESS=DEFLATE", "PREDICTOR=3", "TILED=NO"])
    ds = gdal.Open(dem_path)
    return ds.GetRasterBand(1).ReadAsArray().astype(np.float64), ds.GetGeoTransform(), srs


def clip_to_window(lines, r0, c0, rows, cols):
    """Keep the longest inside run of each traced line, in window coordinates."""
    out = []
    for cells in lines:
        run, best = [], []
        for r, c in cells:
            if r0 <= r < r0 + rows and c0 <= c < c0 + cols:
                run.append((r - r0, c - c0))
            else:
                if len(run) > len(best):
                    best = run
                run = []
        if len(run) > len(best):
            best = run
        out.append(best)
    return out


def make_rivers_and_ridges(dem, gt):
    """Traces on the whole Olinda DEM (so the catchments are complete), then clips."""
    source = gdal.Open(OLINDA)  # keep the dataset alive while its band is read
    full = source.GetRasterBand(1).ReadAsArray().astype(np.float64)
    receiver, order = priority_flood_receivers(full)
    acc = flow_accumulation(receiver, order)
    rivers = clip_to_window(trace_channels(receiver, acc, threshold=120, min_cells=12), CROP_Y, CROP_X, CROP_H, CROP_W)
    rivers = [(cells, int(acc[r + CROP_Y, c + CROP_X])) for cells, (r, c) in
              ((cells, cells[-1]) for cells in rivers if len(cells) >= 10)]

    inv_receiver, inv_order = priority_flood_receivers(-full)
    inv_acc = flow_accumulation(inv_receiver, inv_order)
    ridge_lines = clip_to_window(trace_channels(inv_receiver, inv_acc, threshold=25, min_cells=10),
                                 CROP_Y, CROP_X, CROP_H, CROP_W)
    # Keep the three longest ridges that stay high (on the plateau, not in the plain).
    high = np.percentile(dem, 60)
    ridge_lines = [cells for cells in ridge_lines if len(cells) >= 10 and
                   np.mean([dem[r, c] for r, c in cells]) > high]
    ridge_lines.sort(key=lambda cells: (-len(cells), cells[0]))
    return rivers, ridge_lines[:3]


def new_layer(ds, name, srs, geom_type, fields):
    options = ["FID=fid"] if ds.GetDriver().GetName() == "GPKG" else []
    layer = ds.CreateLayer(name, srs, geom_type, options=options)
    for field_name, field_type in fields:
        layer.CreateField(ogr.FieldDefn(field_name, field_type))
    return layer


def add_feature(layer, geometry, **attributes):
    feature = ogr.Feature(layer.GetLayerDefn())
    for key, value in attributes.items():
        feature.SetField(key, value)
    feature.SetGeometry(geometry)
    layer.CreateFeature(feature)


def line(points):
    g = ogr.Geometry(ogr.wkbLineString)
    for x, y in points:
        g.AddPoint_2D(float(round(x, 2)), float(round(y, 2)))
    return g


def polygon(points):
    ring = ogr.Geometry(ogr.wkbLinearRing)
    for x, y in list(points) + [points[0]]:
        ring.AddPoint_2D(float(round(x, 2)), float(round(y, 2)))
    g = ogr.Geometry(ogr.wkbPolygon)
    g.AddGeometry(ring)
    return g


def rectangle(cx, cy, length, width, angle_deg):
    a = math.radians(angle_deg)
    u, v = (math.cos(a), math.sin(a)), (-math.sin(a), math.cos(a))
    return [(cx + su * length / 2 * u[0] + sv * width / 2 * v[0], cy + su * length / 2 * u[1] + sv * width / 2 * v[1])
            for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1))]


def make_map(out_dir, dem, gt, srs):
    ox, oy = gt[0], gt[3]

    def local(x, y):  # drawn coordinates: metres east and south of the crop's upper-left corner
        return (ox + x, oy - y)

    path = os.path.join(out_dir, "map.gpkg")
    if os.path.exists(path):
        os.remove(path)
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(path)

    roads = new_layer(ds, "roads", srs, ogr.wkbLineString,
                      [("name", ogr.OFTString), ("width", ogr.OFTReal), ("kind", ogr.OFTString)])
    # Closed ring road around a patch of the northern plateau (first point == last point).
    cx, cy = 2300.0, 1500.0
    ring = [local(cx + (620 + 90 * math.sin(3 * t)) * math.cos(t), cy + (430 + 60 * math.cos(2 * t)) * math.sin(t))
            for t in (2 * math.pi * k / 48 for k in range(48))]
    add_feature(roads, line(ring + [ring[0]]), name="Plateau ring road", width=8.0, kind="ring")
    # North-south road descending into the main valley and crossing its river.
    valley = [local(x, y) for x, y in [(4300, 300), (4380, 1400), (4250, 2600), (4420, 3800),
                                        (4600, 4700), (4550, 5700), (4700, 6900)]]
    add_feature(roads, line(valley), name="Valley crossing", width=10.0, kind="primary")
    # Two roads that meet at one shared end point (a junction) on the ring's east side.
    junction = local(3600, 2400)
    add_feature(roads, line([local(1200, 3600), local(1900, 3300), local(2700, 2900), junction]),
                name="West spur", width=6.0, kind="secondary")
    add_feature(roads, line([junction, local(3950, 2050), local(4330, 1850)]),
                name="East spur", width=5.0, kind="secondary")
    add_feature(roads, line([local(500, 5400), local(1500, 5150), local(2600, 5300), local(3500, 5050)]),
                name="Lowland track", width=4.0, kind="track")

    rivers_layer = new_layer(ds, "rivers", srs, ogr.wkbLineString,
                             [("name", ogr.OFTString), ("width", ogr.OFTReal),
                              ("upstream_km2", ogr.OFTReal), ("source", ogr.OFTString)])
    rivers, ridge_lines = make_rivers_and_ridges(dem, gt)
    cell_km2 = abs(gt[1] * gt[5]) / 1e6
    river_lines = smooth_network([cells for cells, _ in rivers], gt, snap_distance=2 * gt[1])
    for i, ((cells, outlet_acc), points) in enumerate(zip(rivers, river_lines)):
        area = outlet_acc * cell_km2
        width = round(min(20.0, 4.0 + 2.0 * math.sqrt(area)), 1)
        add_feature(rivers_layer, line(points), name=f"stream {i + 1}", width=width,
                    upstream_km2=round(area, 2), source="D8 flow accumulation of the Olinda DEM")

    ridges = new_layer(ds, "ridges", srs, ogr.wkbLineString, [("name", ogr.OFTString), ("width", ogr.OFTReal)])
    for i, points in enumerate(smooth_network(ridge_lines, gt, snap_distance=2 * gt[1])):
        add_feature(ridges, line(points), name=f"crest {i + 1}", width=60.0)

    existing = new_layer(ds, "existing", srs, ogr.wkbPolygon, [("name", ogr.OFTString), ("kind", ogr.OFTString)])
    lake = [local(2000 + 380 * math.cos(t) + 40 * math.sin(5 * t), 6200 + 200 * math.sin(t))
            for t in (2 * math.pi * k / 32 for k in range(32))]
    add_feature(existing, polygon(lake), name="Lagoa", kind="lake")
    add_feature(existing, polygon([local(5600, 900), local(6900, 1000), local(7000, 2300), local(5800, 2500)]),
                name="Mata reserve", kind="protected")
    for j, (bx, by, angle) in enumerate([(2330, 1500, 10), (2420, 1430, 12), (2230, 1580, 8),
                                          (4500, 3300, 95), (4520, 3380, 92)]):
        add_feature(existing, polygon(rectangle(*local(bx, by), 18.0, 11.0, angle)), name=f"building {j + 1}",
                    kind="building")
    ds = None


def make_wgs84(out_dir, wdbii_text):
    west, south, east, north = LUX_BOX
    dem_path = os.path.join(out_dir, "dem_wgs84.tif")
    gdal.Translate(dem_path, LUXEMBOURG, projWin=[west, north, east, south],
                   creationOptions=["COMPRESS=DEFLATE", "PREDICTOR=2"])
    segments, current = [], []
    for text_line in open(wdbii_text):
        if text_line.startswith(">"):
            if len(current) > 1:
                segments.append(current)
            current = []
            continue
        lon, lat = map(float, text_line.split()[:2])
        current.append((lon, lat))
    if len(current) > 1:
        segments.append(current)
    box = ogr.CreateGeometryFromWkt(
        f"POLYGON(({west} {south},{east} {south},{east} {north},{west} {north},{west} {south}))")
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(4326)
    srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    path = os.path.join(out_dir, "lines_wgs84.geojson")
    if os.path.exists(path):
        os.remove(path)
    ds = ogr.GetDriverByName("GeoJSON").CreateDataSource(path)
    layer = new_layer(ds, "lines_wgs84", srs, ogr.wkbLineString, [("name", ogr.OFTString), ("width", ogr.OFTReal),
                                                                  ("kind", ogr.OFTString)])
    merged = ogr.Geometry(ogr.wkbMultiLineString)
    for seg in segments:
        merged.AddGeometry(line(seg))
    clipped = ogr.ForceToMultiLineString(merged.Intersection(box))
    for part in clipped:
        if part.Length() > 0.01:  # degrees; drops slivers cut at the box edge
            add_feature(layer, part.Clone(), name="Moselle (WDBII)", width=90.0, kind="river")
    add_feature(layer, line([(6.17, 49.50), (6.22, 49.55), (6.27, 49.59), (6.31, 49.64)]), name="Drawn road",
                width=7.0, kind="road")
    ds = None


# --- preview for docs/data.md ---

MAP_SIZE = 720
LAYER_STYLE = {  # layer: (colour, minimum drawn width in preview pixels)
    "existing": ((200, 60, 60), 1),
    "ridges": ((150, 90, 20), 3),
    "rivers": ((30, 110, 230), 2),
    "roads": ((20, 20, 20), 3),
}


def hillshade_rgb(dem_path, size):
    shade = gdal.DEMProcessing("", dem_path, "hillshade", format="MEM", zFactor=4.0, computeEdges=True)
    grey = shade.GetRasterBand(1).ReadAsArray().astype(np.float64)
    source = gdal.Open(dem_path)
    z = source.GetRasterBand(1).ReadAsArray().astype(np.float64)
    t = (z - z.min()) / max(1e-9, z.max() - z.min())
    tint = np.stack([0.55 + 0.45 * t, 0.75 + 0.2 * t, 0.45 + 0.3 * t], axis=-1)  # green lowland, tan plateau
    rgb = np.clip(tint * (0.35 + 0.65 * grey[..., None] / 255.0) * 255.0, 0, 255).astype(np.uint8)
    return Image.fromarray(rgb).resize((size, size), Image.BICUBIC), source.GetGeoTransform(), z.shape


def draw_map(samples_dir, out_path):
    image, gt, (rows, cols) = hillshade_rgb(os.path.join(samples_dir, "dem.tif"), MAP_SIZE)
    draw = ImageDraw.Draw(image)
    sx, sy = MAP_SIZE / cols, MAP_SIZE / rows

    def to_px(x, y):
        return ((x - gt[0]) / gt[1] * sx, (y - gt[3]) / gt[5] * sy)

    metres_per_px = gt[1] / sx
    ds = ogr.Open(os.path.join(samples_dir, "map.gpkg"))
    for name, (colour, min_width) in LAYER_STYLE.items():
        layer = ds.GetLayerByName(name)
        for feature in layer:
            geometry = feature.GetGeometryRef()
            if geometry.GetGeometryType() == ogr.wkbPolygon:
                ring = geometry.GetGeometryRef(0)
                points = [to_px(*ring.GetPoint_2D(i)) for i in range(ring.GetPointCount())]
                draw.polygon(points, outline=colour, width=2)
                continue
            width = max(min_width, int(round(feature.GetField("width") / metres_per_px)))
            points = [to_px(*geometry.GetPoint_2D(i)) for i in range(geometry.GetPointCount())]
            draw.line(points, fill=colour, width=width, joint="curve")
    # Scale bar: 1 km.
    bar = 1000.0 / metres_per_px
    draw.rectangle([20, MAP_SIZE - 30, 20 + bar, MAP_SIZE - 24], fill=(0, 0, 0))
    draw.text((20, MAP_SIZE - 46), "1 km", fill=(0, 0, 0))
    draw.text((20, 12), "roads (black)  rivers (blue)  ridges (brown)  existing (red)", fill=(0, 0, 0))
    image.save(out_path, optimize=True)


def main():
    out_dir, wdbii_text, images_dir = sys.argv[1], sys.argv[2], sys.argv[3]
    os.makedirs(out_dir, exist_ok=True)
    os.makedirs(images_dir, exist_ok=True)
    dem, gt, srs = make_dem(out_dir)
    make_map(out_dir, dem, gt, srs)
    make_wgs84(out_dir, wdbii_text)
    draw_map(out_dir, os.path.join(images_dir, "sample_map.png"))


if __name__ == "__main__":
    main()
