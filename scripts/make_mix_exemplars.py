#!/usr/bin/python3
"""Draws the exemplars of the exemplar-mix demos (pipelines/mix.yaml, docs/synthesis.md) into
samples/exemplars/, with numpy and GDAL only: each shares the band of the exemplar it mixes
with, so that seams across the mix are meaningful.
  bridge_deck_240x64   the band of road_lanes_240x64 (rows 14..50): a concrete deck, kerbs
                       with railing posts, expansion joints. Height: kerbs 0.25 m.
  crossing_240x64      road_lanes_240x64 with zebra stripes across it. Height: 0.
  sand_band_260x80     the band of rock_band_260x80 (rows 18..62): rippled sand and a few
                       pebbles. Height: ripples up to 0.06 m.
  cobble_bed_260x80    cobbles bedded in sand_band_260x80 (its texels where no cobble lies,
                       the same band): the river bed the sand alternates with. Height: cobble
                       domes up to 0.5 m on the ripples.
Usage: make_mix_exemplars.py [EXEMPLAR_DIR]. Deterministic (numpy default_rng, fixed seeds);
shapes are drawn 4x larger and box-filtered down, as make_exemplars.py does.
"""
import os
import sys

import numpy as np
from osgeo import gdal

from exemplar_files import write_height, write_png

gdal.UseExceptions()
SS = 4


def grid(width, height):
    yy, xx = np.mgrid[0:height * SS, 0:width * SS]
    return (xx + 0.5) / SS, (yy + 0.5) / SS


def finish(rgb, alpha, height_m):
    """Supersampled rgb (0..255), alpha (0..1), height -> RGBA8 and float32 height."""
    h, w = alpha.shape[0] // SS, alpha.shape[1] // SS
    box = lambda a: a.reshape(h, SS, w, SS, *a.shape[2:]).mean(axis=(1, 3))
    a = box(alpha)
    colour = box(rgb * alpha[..., None]) / np.maximum(a, 1e-9)[..., None]
    height = np.where(a > 0, box(height_m * alpha) / np.maximum(a, 1e-9), 0.0)
    rgba = np.concatenate([np.where(a[..., None] > 0, colour, 0.0), a[..., None] * 255.0], axis=-1)
    return np.clip(np.rint(rgba), 0, 255).astype(np.uint8), height.astype(np.float32)


def write(out_dir, name, rgba, height_m):
    write_png(os.path.join(out_dir, name + ".png"), rgba)
    write_height(os.path.join(out_dir, name + "_height.tif"), height_m)


def bridge_deck(rng):
    x, y = grid(240, 64)
    top, bottom = 14.0, 50.0
    rgb = np.array([150.0, 148.0, 142.0]) + 6.0 * rng.normal(size=x.shape)[..., None]
    alpha = ((y >= top) & (y < bottom)).astype(float)
    kerb = ((y >= top) & (y < top + 4)) | ((y >= bottom - 4) & (y < bottom))
    rgb[kerb] = [196.0, 194.0, 188.0]
    posts = np.cumsum(8.0 + rng.uniform(-0.5, 0.5, size=40)) + rng.uniform(0, 8) - 8.0
    for p in posts:
        rgb[kerb & (x >= p) & (x < p + 1.5)] = [60.0, 62.0, 66.0]
    joints = np.cumsum(40.0 + rng.uniform(-4, 4, size=8)) + rng.uniform(10, 30) - 40.0
    for j in joints:
        rgb[~kerb & (y >= top) & (y < bottom) & (x >= j) & (x < j + 1.2)] = [90.0, 90.0, 92.0]
    return finish(rgb, alpha, np.where(kerb, 0.25, 0.0))


def crossing(rng, road_lanes_png):
    road = gdal.Open(road_lanes_png).ReadAsArray().transpose(1, 2, 0).astype(float)
    road = np.repeat(np.repeat(road, SS, axis=0), SS, axis=1)
    x, y = grid(240, 64)
    rgb, alpha = road[..., :3].copy(), road[..., 3] / 255.0
    starts = np.cumsum(12.0 + rng.uniform(-0.4, 0.4, size=24)) + rng.uniform(0, 4) - 12.0
    for s in starts:
        width = 6.0 + rng.uniform(-0.4, 0.4)
        rgb[(y >= 18.0) & (y < 46.0) & (x >= s) & (x < s + width)] = [238.0, 238.0, 232.0]
    return finish(rgb, alpha, np.zeros_like(alpha))


def sand(rng):
    """The sand band's supersampled grid, colour, band mask and ripple."""
    x, y = grid(260, 80)
    phase = np.cumsum(rng.normal(0.0, 0.05, size=x.shape[1])) / SS
    ripple = 0.5 + 0.5 * np.sin(2 * np.pi * (x / 9.0 + 0.15 * np.sin(y / 7.0) + phase[None, :]))
    rgb = np.array([196.0, 176.0, 132.0]) * (0.88 + 0.12 * ripple[..., None])
    rgb = rgb + 5.0 * rng.normal(size=x.shape)[..., None]
    inside = (y >= 18.0 + 1.5 * np.sin(x / 23.0)) & (y < 62.0 - 1.5 * np.sin(x / 19.0 + 1.0))
    for _ in range(25):
        cx, cy, r = rng.uniform(0, 260), rng.uniform(26, 54), rng.uniform(1.0, 2.2)
        pebble = ((x - cx) / r) ** 2 + ((y - cy) / (0.8 * r)) ** 2 <= 1.0
        rgb[pebble] = np.array([128.0, 118.0, 104.0]) * rng.uniform(0.8, 1.1)
    return x, y, rgb, inside, ripple


def sand_band(rng):
    x, y, rgb, inside, ripple = sand(rng)
    return finish(rgb, inside.astype(float), np.where(inside, 0.06 * ripple, 0.0))


def cobble_bed(rng):
    """Cobbles bedded in the sand band: the sand's texels wherever no cobble lies, so that
    seams between the two exemplars are as cheap as the sand's own where the bed is bare."""
    x, y, rgb, inside, ripple = sand(np.random.default_rng(9))
    height = np.where(inside, 0.06 * ripple, 0.0)
    for _ in range(70):
        cx, cy = rng.uniform(-4, 264), rng.uniform(22, 58)
        rx = rng.uniform(2.5, 6.0)
        ry = rx * rng.uniform(0.6, 0.9)
        d2 = ((x - cx) / rx) ** 2 + ((y - cy) / ry) ** 2
        cobble = (d2 <= 1.0) & inside
        shade = np.array([126.0, 122.0, 116.0]) * rng.uniform(0.75, 1.1)
        light = 0.8 + 0.35 * (1.0 - d2[cobble]) - 0.15 * (y[cobble] - cy) / ry
        rgb[cobble] = shade * light[..., None]
        dome = 0.5 * rx / 6.0 * np.sqrt(np.clip(1.0 - d2, 0.0, 1.0))
        height = np.where(cobble, np.maximum(height, dome), height)
    return finish(rgb, inside.astype(float), height)


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else "samples/exemplars"
    write(out_dir, "bridge_deck_240x64", *bridge_deck(np.random.default_rng(7)))
    write(out_dir, "crossing_240x64",
          *crossing(np.random.default_rng(8), os.path.join(out_dir, "road_lanes_240x64.png")))
    write(out_dir, "sand_band_260x80", *sand_band(np.random.default_rng(9)))
    write(out_dir, "cobble_bed_260x80", *cobble_bed(np.random.default_rng(10)))


if __name__ == "__main__":
    main()
