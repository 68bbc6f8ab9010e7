#!/usr/bin/python3
"""Draws the exemplars that dress grown ornaments (docs/ornaments.md, "In a pipeline") into
samples/exemplars/: hedge_192x48.png, a hedgerow of overlapping shrubs seen from above, and
dry_wall_200x40.png, a dry-stone wall of irregular stones in two courses, with its height
channel dry_wall_200x40_height.tif (metres above the wall's top, 0 where transparent).

Same conventions as make_exemplars.py (RGBA, the pattern runs horizontally through the middle,
transparent above and below; drawn 4x larger and box-filtered down so edges are anti-aliased in
alpha; every irregularity from numpy's default_rng with a fixed seed), but numpy and GDAL only,
so it runs where Pillow is not installed. Usage: make_ornament_exemplars.py [EXEMPLAR_DIR]
"""
import math
import os
import sys

import numpy as np
from osgeo import gdal

from exemplar_files import write_height, write_png

gdal.UseExceptions()

SS = 4  # supersampling factor


class Canvas:
    """Premultiplied-free RGBA + height at SS x the final size, painted back to front."""

    def __init__(self, width, height):
        self.width, self.height = width, height
        self.rgb = np.zeros((height * SS, width * SS, 3))
        self.alpha = np.zeros((height * SS, width * SS))
        self.height_m = np.zeros((height * SS, width * SS))
        self.ys, self.xs = np.mgrid[0:height * SS, 0:width * SS] / SS + 0.5 / SS

    def blob(self, rng, cx, cy, rx, ry, roughness):
        """The mask of an irregular blob (three harmonics of the radius) and its normalised
        radius r in [0, 1) inside it, on the supersampled grid."""
        phase = rng.uniform(0, 2 * math.pi, size=3)
        dx, dy = (self.xs - cx) / rx, (self.ys - cy) / ry
        t = np.arctan2(dy, dx)
        edge = 1.0 + roughness * sum(np.sin((k + 2) * t + phase[k]) / (k + 2) for k in range(3))
        r = np.hypot(dx, dy) / edge
        return r < 1.0, r

    def paint(self, mask, rgb, height=None):
        self.rgb[mask] = rgb[mask] if rgb.ndim == 3 else rgb
        self.alpha[mask] = 1.0
        if height is not None:
            self.height_m[mask] = height[mask]

    def finish(self):
        def down(a):
            return a.reshape(self.height, SS, self.width, SS, *a.shape[2:]).mean(axis=(1, 3))

        a = down(self.alpha)
        colour = down(self.rgb * self.alpha[..., None]) / np.maximum(a[..., None], 1e-9)
        h = down(self.height_m * self.alpha) / np.maximum(a, 1e-9)
        rgba = np.dstack([np.where(a[..., None] > 0, colour, 0.0), a * 255.0])
        return (np.clip(np.rint(rgba), 0, 255).astype(np.uint8),
                np.where(a > 0, h, 0.0).astype(np.float32))


def leaf_noise(rng, canvas, cell):
    """Texture of leaves or grain: uniform noise in [-1, 1] on cells of `cell` final texels."""
    h = -(-canvas.height * SS // (cell * SS))
    w = -(-canvas.width * SS // (cell * SS))
    coarse = rng.uniform(-1.0, 1.0, size=(h, w))
    return np.kron(coarse, np.ones((cell * SS, cell * SS)))[:canvas.height * SS, :canvas.width * SS]


def hedge(rng):
    """192x48 (24 m at 8 texels per metre): shrubs 1.2-2.4 m across along the middle row, each
    lit from the upper left, over leaf-sized noise; a few narrow gaps between clumps."""
    c = Canvas(192, 48)
    leaves = leaf_noise(rng, c, 1)
    shrubs, x = [], -6.0
    while x < 192 + 6:
        radius = rng.uniform(5.0, 9.5)
        shrubs.append((x, 24.0 + rng.normal(0.0, 1.6), radius))
        x += radius * rng.uniform(0.9, 1.4) + (rng.uniform(3.0, 5.0) if rng.uniform() < 0.12 else 0.0)
    greens = [np.array(v, dtype=np.float64) for v in ((52, 92, 40), (66, 104, 46), (44, 80, 44))]
    for i in rng.permutation(len(shrubs)):  # overlap order irregular, not left to right
        cx, cy, radius = shrubs[i]
        ry = min(radius * rng.uniform(0.8, 1.0), 23.0 - abs(cy - 24.0))  # inside rows 1..47
        mask, r = c.blob(rng, cx, cy, radius, ry, 0.25)
        base = greens[int(rng.integers(len(greens)))] * rng.uniform(0.85, 1.15)
        # Lit from the upper left: brighter towards (-x, -y) of the shrub's centre, darker rim.
        toward_light = -((c.xs - cx) + (c.ys - cy)) / (math.sqrt(2) * radius)
        light = 0.8 + 0.25 * toward_light + 0.25 * (1.0 - r) + 0.12 * leaves
        c.paint(mask, np.clip(base[None, None, :] * light[..., None], 0, 255))
    return c


def dry_wall(rng):
    """200x40 (25 m at 8 texels per metre): a wall about 1.2 m thick, two courses of irregular
    stones 0.5-1.2 m long with dark joints between them (transparent). Height: 0.08-0.2 m domes."""
    c = Canvas(200, 40)
    grain = leaf_noise(rng, c, 1)
    for top, bottom in ((15.0, 20.0), (20.0, 25.0)):
        x = rng.uniform(-8.0, -2.0)
        while x < 200:
            length = rng.uniform(4.0, 9.5)
            cy = (top + bottom) / 2 + rng.uniform(-0.4, 0.4)
            mask, r = c.blob(rng, x + length / 2, cy, length / 2, (bottom - top) / 2 + 0.3, 0.12)
            tone = rng.uniform(0.8, 1.2)
            base = np.array((146, 140, 128) if rng.uniform() < 0.6 else (124, 124, 120)) * tone
            light = 0.85 + 0.22 * (1.0 - r) - 0.1 * (c.ys - cy) / 3.0 + 0.08 * grain
            peak = rng.uniform(0.08, 0.2)
            c.paint(mask, np.clip(base[None, None, :] * light[..., None], 0, 255),
                    peak * np.sqrt(np.clip(1.0 - r * r, 0.05, 1.0)))
            x += length + rng.uniform(0.4, 1.1)
    return c


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "samples", "exemplars")
    os.makedirs(out_dir, exist_ok=True)
    rgba, _ = hedge(np.random.default_rng(21)).finish()
    write_png(os.path.join(out_dir, "hedge_192x48.png"), rgba, ["ZLEVEL=9"])
    rgba, height_m = dry_wall(np.random.default_rng(22)).finish()
    write_png(os.path.join(out_dir, "dry_wall_200x40.png"), rgba, ["ZLEVEL=9"])
    write_height(os.path.join(out_dir, "dry_wall_200x40_height.tif"), height_m)


if __name__ == "__main__":
    main()
