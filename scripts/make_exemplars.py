#!/usr/bin/python3
"""Draws the exemplars of samples/exemplars/ (RGBA PNG, the pattern runs horizontally
through the middle of the image, transparent above and below) and the montage
docs/images/exemplars.png. Usage: make_exemplars.py EXEMPLAR_DIR IMAGES_DIR [DEM MAP]

Deterministic: every irregularity comes from numpy's default_rng with a fixed seed.
Shapes are drawn 4x larger and box-filtered down, so edges are anti-aliased in alpha.
Some exemplars have a height channel in metres as a separate single-band Float32
GeoTIFF NAME_height.tif of the same size (0 where alpha is 0).
The ridge band is cut from the real DEM (samples/dem.tif) along a crest of
samples/map.gpkg (layer ridges), so run make_samples.py first.
"""
import math
import os
import sys

import numpy as np
from osgeo import gdal, ogr
from PIL import Image, ImageDraw

from exemplar_files import write_height

gdal.UseExceptions()
ogr.UseExceptions()

SS = 4  # supersampling factor


class Canvas:
    """RGBA + height drawn at SS x the final size."""

    def __init__(self, width, height):
        self.width, self.height = width, height
        self.image = Image.new("RGBA", (width * SS, height * SS), (0, 0, 0, 0))
        self.draw = ImageDraw.Draw(self.image)
        self.height_m = np.zeros((height * SS, width * SS), dtype=np.float64)

    def s(self, points):
        return [(x * SS, y * SS) for x, y in points]

    def finish(self):
        rgba = np.asarray(self.image, dtype=np.float64)
        alpha = rgba[..., 3:4] / 255.0
        premultiplied = np.concatenate([rgba[..., :3] * alpha, alpha], axis=-1)
        small = premultiplied.reshape(self.height, SS, self.width, SS, 4).mean(axis=(1, 3))
        a = small[..., 3:4]
        colour = np.where(a > 0, small[..., :3] / np.maximum(a, 1e-9), 0.0)
        out = np.concatenate([colour, a * 255.0], axis=-1)
        h = self.height_m.reshape(self.height, SS, self.width, SS).mean(axis=(1, 3))
        h = np.where(a[..., 0] > 0, h / np.maximum(a[..., 0], 1e-9), 0.0)  # height of the opaque part
        return np.clip(np.rint(out), 0, 255).astype(np.uint8), h.astype(np.float32)


def shade(colour, factor):
    return tuple(int(max(0, min(255, round(c * factor)))) for c in colour)


def chain(rng):
    """199x82 (the paper's chain size): face-on rings linked by edge-on links, sagging."""
    c = Canvas(199, 82)
    centre = 41.0
    x = 4.0
    links = []
    while x < 199 + 20:
        length = 36.0 + rng.uniform(-3.0, 3.0)
        sag = 4.0 * math.sin(math.pi * x / 199.0) + rng.uniform(-1.5, 1.5)
        links.append((x, length, centre + sag))
        x += length * 0.78 + rng.uniform(-1.5, 1.5)
    steel = (150, 155, 165)
    for i, (x0, length, y) in enumerate(links):
        if i % 2 == 0:  # face-on ring: thick outline, open middle
            half_h = 14.0 + rng.uniform(-1.0, 1.0)
            box = c.s([(x0, y - half_h), (x0 + length, y + half_h)])
            c.draw.ellipse(box, outline=shade(steel, 0.75), width=int(8 * SS))
            inner = c.s([(x0 + 1.5, y - half_h + 1.5), (x0 + length - 1.5, y + half_h - 1.5)])
            c.draw.ellipse(inner, outline=shade(steel, 1.15), width=int(3 * SS))
    for i, (x0, length, y) in enumerate(links):
        if i % 2 == 1:  # edge-on link: a bar threaded through both neighbours
            half_h = 5.0 + rng.uniform(-0.5, 0.5)
            box = c.s([(x0 - 4, y - half_h), (x0 + length + 4, y + half_h)])
            c.draw.rounded_rectangle(box, radius=int(half_h * SS), fill=shade(steel, 0.9))
            c.draw.line(c.s([(x0 - 1, y - 1), (x0 + length + 1, y - 1)]), fill=shade(steel, 1.3), width=SS)
    return c


def braid(rng):
    """325x64 (the paper's size): three strands crossing over and under."""
    c = Canvas(325, 64)
    W, H = c.width * SS, c.height * SS
    xs = np.arange(W) / SS
    ys = (np.arange(H) / SS)[:, None]
    # An irregular phase: the period drifts between about 56 and 72 px.
    period = 64.0 + 8.0 * np.sin(xs / 47.0 + rng.uniform(0, 6.28))
    phase = np.cumsum(2 * math.pi / period / SS)
    colours = [np.array(v, dtype=np.float64) for v in ((196, 160, 96), (150, 110, 60), (220, 196, 140))]
    best_depth = np.full((H, W), -np.inf)
    rgb = np.zeros((H, W, 3))
    alpha = np.zeros((H, W))
    amplitude, half_width = 10.0, 5.2
    for k in range(3):
        theta = phase + 2 * math.pi * k / 3
        centre = 32.0 + amplitude * np.sin(theta)
        slope = amplitude * np.cos(theta) * np.gradient(phase) * SS
        distance = np.abs(ys - centre[None, :]) / np.sqrt(1 + slope[None, :] ** 2)
        depth = np.cos(theta)[None, :].repeat(H, axis=0)
        inside = (distance < half_width) & (depth > best_depth)
        light = 0.65 + 0.45 * np.sqrt(np.clip(1 - (distance / half_width) ** 2, 0, 1))
        # Twisted fibres: diagonal stripes along the strand.
        fibres = 0.9 + 0.1 * np.sign(np.sin((xs[None, :] * 1.3 + ys * 1.0) * 1.2))
        strand = colours[k][None, None, :] * (light * fibres)[..., None]
        rgb = np.where(inside[..., None], strand, rgb)
        alpha = np.where(inside, 1.0, alpha)
        best_depth = np.where(inside, depth, best_depth)
    c.image = Image.fromarray(np.dstack([np.clip(rgb, 0, 255), alpha * 255]).astype(np.uint8), "RGBA")
    return c


def zigzag(rng):
    """156x64 (the paper's size): a painted zigzag with irregular peaks."""
    c = Canvas(156, 64)
    points, x, up = [], -6.0, True
    while x < 156 + 12:
        amplitude = 11.0 + rng.uniform(-3.0, 3.0)
        points.append((x, 32.0 + (-amplitude if up else amplitude)))
        x += 13.0 + rng.uniform(-4.0, 4.0)
        up = not up
    c.draw.line(c.s(points), fill=(120, 40, 30, 255), width=int(9 * SS), joint="curve")
    c.draw.line(c.s(points), fill=(215, 150, 60, 255), width=int(5 * SS), joint="curve")
    return c


def road_lanes(rng):
    """240x64: asphalt with solid edge lines and an irregular dashed centre line.
    Height: cross-fall camber, 0.12 m at the crown, 0 at the edges."""
    c = Canvas(240, 64)
    top, bottom = 14.0, 50.0
    W = c.width * SS
    noise = rng.normal(0.0, 1.0, size=(c.height * SS, W))
    base = np.array([70.0, 72.0, 76.0])
    rgb = base[None, None, :] + 9.0 * noise[..., None]
    image = np.zeros((c.height * SS, W, 4))
    image[..., :3] = rgb
    rows = np.arange(c.height * SS) / SS
    on_road = (rows >= top) & (rows < bottom)
    image[on_road, :, 3] = 255
    c.image = Image.fromarray(np.clip(image, 0, 255).astype(np.uint8), "RGBA")
    c.draw = ImageDraw.Draw(c.image)
    # A few darker patches (repairs) so synthesis has choices.
    for _ in range(4):
        x0 = rng.uniform(10, 220)
        c.draw.rectangle(c.s([(x0, top + rng.uniform(4, 10)), (x0 + rng.uniform(8, 18), top + rng.uniform(16, 30))]),
                         fill=(52, 54, 58, 255))
    white = (235, 235, 228, 255)
    c.draw.rectangle(c.s([(0, top + 2), (240, top + 3.5)]), fill=white)
    c.draw.rectangle(c.s([(0, bottom - 3.5), (240, bottom - 2)]), fill=white)
    x = rng.uniform(0, 6)
    while x < 240:
        dash = 14.0 + rng.uniform(-3, 3)
        c.draw.rectangle(c.s([(x, 31.0), (min(240, x + dash), 33.0)]), fill=(232, 200, 60, 255))
        x += dash + 10.0 + rng.uniform(-3, 3)
    t = (rows - top) / (bottom - top)
    camber = np.where(on_road, 0.12 * (1 - (2 * t - 1) ** 2), 0.0)
    c.height_m = np.repeat(camber[:, None], W, axis=1)
    return c


def irregular_blob(rng, cx, cy, rx, ry, roughness, n=18):
    phase = rng.uniform(0, 2 * math.pi, size=3)
    points = []
    for i in range(n):
        t = 2 * math.pi * i / n
        r = 1.0 + roughness * sum(math.sin((k + 2) * t + phase[k]) / (k + 2) for k in range(3))
        points.append((cx + rx * r * math.cos(t), cy + ry * r * math.sin(t)))
    return points


def paint_dome(c, polygon, peak_m):
    """Height of a stone: a dome over the polygon's mask (distance-based, capped)."""
    mask_image = Image.new("L", (c.width * SS, c.height * SS), 0)
    ImageDraw.Draw(mask_image).polygon(c.s(polygon), fill=255)
    mask = np.asarray(mask_image) > 0
    ys, xs = np.nonzero(mask)
    if len(xs) == 0:
        return
    cx, cy = xs.mean(), ys.mean()
    rx, ry = max(1.0, (xs.max() - xs.min()) / 2), max(1.0, (ys.max() - ys.min()) / 2)
    d2 = ((xs - cx) / rx) ** 2 + ((ys - cy) / ry) ** 2
    c.height_m[ys, xs] = np.maximum(c.height_m[ys, xs], peak_m * np.sqrt(np.clip(1 - d2, 0.05, 1)))


def cobble_edging(rng):
    """200x56: one row of setts of varying width with transparent joints. Height: 0.1 m domes."""
    c = Canvas(200, 56)
    x = -4.0
    while x < 200:
        width = 11.0 + rng.uniform(-2.5, 3.5)
        top, bottom = 16.0 + rng.uniform(-1.2, 1.2), 40.0 + rng.uniform(-1.2, 1.2)
        stone = irregular_blob(rng, x + width / 2, (top + bottom) / 2, width / 2, (bottom - top) / 2, 0.08, n=24)
        # Setts are squarish: pull the blob towards its bounding rectangle.
        stone = [(0.45 * px + 0.55 * min(max(px, x), x + width), 0.45 * py + 0.55 * min(max(py, top), bottom))
                 for px, py in stone]
        tone = rng.uniform(0.85, 1.15)
        c.draw.polygon(c.s(stone), fill=shade((150, 140, 128), tone) + (255,))
        c.draw.polygon(c.s([(px * 0.8 + (x + width / 2) * 0.2, py * 0.8 + (top + bottom) / 2 * 0.2 - 1)
                            for px, py in stone]), fill=shade((172, 162, 148), tone) + (255,))
        paint_dome(c, stone, 0.10)
        x += width + 1.6 + rng.uniform(0, 1.0)
    return c


def rock_band(rng):
    """260x80: a band of overlapping boulders, larger in the middle. Height: up to 0.8 m."""
    c = Canvas(260, 80)
    rocks = []
    for _ in range(70):
        x = rng.uniform(-6, 266)
        y = 40 + rng.normal(0, 6.0)
        size = rng.uniform(4.0, 11.0) * (1.2 - abs(y - 40) / 40)
        rocks.append((y + size, x, y, size))  # farther (higher up) rocks first
    for _, x, y, size in sorted(rocks):
        y = min(max(y, 18 + size * 0.8), 62 - size * 0.8)  # keep the band inside rows 18..62
        outline = irregular_blob(rng, x, y, size, size * rng.uniform(0.6, 0.85), 0.35)
        tone = rng.uniform(0.75, 1.2)
        base = (128, 118, 104) if rng.uniform() < 0.6 else (110, 112, 116)
        c.draw.polygon(c.s(outline), fill=shade(base, tone * 0.8) + (255,))
        lit = [(px * 0.7 + (x - size * 0.2) * 0.3, py * 0.7 + (y - size * 0.2) * 0.3) for px, py in outline]
        c.draw.polygon(c.s(lit), fill=shade(base, tone * 1.1) + (255,))
        paint_dome(c, outline, 0.08 * size)
    return c


def bilinear(z, gt, x, y):
    col = (x - gt[0]) / gt[1] - 0.5
    row = (y - gt[3]) / gt[5] - 0.5
    col = np.clip(col, 0, z.shape[1] - 1.001)
    row = np.clip(row, 0, z.shape[0] - 1.001)
    c0, r0 = np.floor(col).astype(int), np.floor(row).astype(int)
    fc, fr = col - c0, row - r0
    return ((z[r0, c0] * (1 - fc) + z[r0, c0 + 1] * fc) * (1 - fr) +
            (z[r0 + 1, c0] * (1 - fc) + z[r0 + 1, c0 + 1] * fc) * fr)


def ridge_band(dem_path, map_path, width=200, height=64, along_step=25.0, across_step=22.0):
    """The longest crest of map.gpkg straightened: column = arc length along the crest,
    row = signed offset across it. Alpha where the terrain stands above its
    cross-section's floor by more than 60 % of the crest's relief; height channel =
    elevation above that floor (metres)."""
    source = gdal.Open(dem_path)
    z = source.GetRasterBand(1).ReadAsArray().astype(np.float64)
    gt = source.GetGeoTransform()
    ds = ogr.Open(map_path)
    layer = ds.GetLayerByName("ridges")
    crests = [f.GetGeometryRef().Clone() for f in layer]
    crest = max(crests, key=lambda g: g.Length())
    pts = np.array([crest.GetPoint_2D(i) for i in range(crest.GetPointCount())])
    seg = np.hypot(*np.diff(pts, axis=0).T)
    s = np.concatenate([[0], np.cumsum(seg)])
    start = max(0.0, (s[-1] - width * along_step) / 2)
    along = start + np.arange(width) * along_step
    cx, cy = np.interp(along, s, pts[:, 0]), np.interp(along, s, pts[:, 1])
    # Smoothed tangent so the cross-sections do not fan out at bends.
    window = np.ones(31) / 31
    tx = np.gradient(np.convolve(np.pad(cx, 15, mode="edge"), window, "valid"))
    ty = np.gradient(np.convolve(np.pad(cy, 15, mode="edge"), window, "valid"))
    norm = np.hypot(tx, ty)
    nx, ny = -ty / norm, tx / norm
    across = (np.arange(height) - (height - 1) / 2) * across_step
    X = cx[None, :] + across[:, None] * nx[None, :]
    Y = cy[None, :] + across[:, None] * ny[None, :]
    elevation = bilinear(z, gt, X, Y)
    floor = elevation.min(axis=0, keepdims=True)
    crest_top = elevation[height // 2 - 6:height // 2 + 7].max(axis=0, keepdims=True)
    relative = elevation - floor
    threshold = 0.6 * (crest_top - floor)
    alpha = np.clip((relative - threshold) / 3.0 + 0.5, 0, 1)
    rows = np.abs(np.arange(height) - (height - 1) / 2)[:, None]
    alpha *= np.clip((0.34 * height - rows) / 2.0, 0, 1)  # keep a transparent margin above and below
    # Hillshade (light from the upper left of the image) and an elevation tint.
    dzdx = np.gradient(elevation, axis=1) / along_step
    dzdy = np.gradient(elevation, axis=0) / across_step
    light = np.clip(0.8 + 1.5 * (-dzdx - dzdy) / np.sqrt(2), 0.45, 1.15)
    t = np.clip(relative / max(1e-9, relative.max()), 0, 1)
    tint = np.stack([110 + 90 * t, 120 + 60 * t, 70 + 40 * t], axis=-1)
    rgb = np.clip(tint * light[..., None], 0, 255)
    rgba = np.dstack([np.where(alpha[..., None] > 0, rgb, 0), alpha * 255])
    height_m = np.where(alpha > 0, relative, 0.0).astype(np.float32)
    return np.rint(rgba).astype(np.uint8), height_m


def write(out_dir, name, rgba, height_m=None):
    Image.fromarray(rgba, "RGBA").save(os.path.join(out_dir, name + ".png"), optimize=True)
    if height_m is not None:
        write_height(os.path.join(out_dir, name + "_height.tif"), height_m)


def main():
    out_dir, images_dir = sys.argv[1], sys.argv[2]
    dem = sys.argv[3] if len(sys.argv) > 3 else "samples/dem.tif"
    map_path = sys.argv[4] if len(sys.argv) > 4 else "samples/map.gpkg"
    os.makedirs(out_dir, exist_ok=True)
    os.makedirs(images_dir, exist_ok=True)
    drawn = [("chain_199x82", chain, 1, False), ("braid_325x64", braid, 2, False),
             ("zigzag_156x64", zigzag, 3, False), ("road_lanes_240x64", road_lanes, 4, True),
             ("cobble_edging_200x56", cobble_edging, 5, True), ("rock_band_260x80", rock_band, 6, True)]
    for name, draw, seed, with_height in drawn:
        rgba, height_m = draw(np.random.default_rng(seed)).finish()
        write(out_dir, name, rgba, height_m if with_height else None)
    rgba, height_m = ridge_band(dem, map_path)
    write(out_dir, "ridge_band_200x64", rgba, height_m)
    draw_montage(out_dir, os.path.join(images_dir, "exemplars.png"))


# --- preview for docs/data.md ---

def checkerboard(width, height, cell=8):
    yy, xx = np.mgrid[0:height, 0:width]
    v = np.where(((xx // cell) + (yy // cell)) % 2 == 0, 235, 200).astype(np.uint8)
    return Image.fromarray(np.stack([v, v, v], axis=-1))


def draw_montage(exemplar_dir, out_path, scale=2):
    files = sorted(f for f in os.listdir(exemplar_dir) if f.endswith(".png"))
    tiles = []
    for name in files:
        tile = Image.open(os.path.join(exemplar_dir, name)).convert("RGBA")
        tile = tile.resize((tile.width * scale, tile.height * scale), Image.NEAREST)
        framed = checkerboard(tile.width, tile.height).convert("RGBA")
        framed.alpha_composite(tile)
        tiles.append((name, framed))
    width = max(t.width for _, t in tiles) + 20
    height = sum(t.height + 24 for _, t in tiles) + 10
    montage = Image.new("RGB", (width, height), (255, 255, 255))
    draw = ImageDraw.Draw(montage)
    y = 6
    for name, tile in tiles:
        draw.text((10, y), f"{name}  ({tile.width // scale}x{tile.height // scale})", fill=(0, 0, 0))
        montage.paste(tile.convert("RGB"), (10, y + 14))
        y += tile.height + 24
    montage.save(out_path, optimize=True)



if __name__ == "__main__":
    main()
