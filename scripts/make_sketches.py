#!/usr/bin/env python3
"""Writes the sample sketches of samples/sketches (structured shape-patterns, docs/shape-patterns.md).

Strokes live in the unit square; `type` is bounded (parts of shapes that repeat) or unbounded
(fibres that go on beyond the square), `material` names the splat material or instance type,
`thickness` is in sketch units. Deterministic: rerun to regenerate the same files.
"""
import json
import math
import os
import sys


def line(a, b, n=8):
    return [[a[0] + (b[0] - a[0]) * k / n, a[1] + (b[1] - a[1]) * k / n] for k in range(n + 1)]


def ring(c, r, n=12):
    return [[c[0] + r * math.cos(2 * math.pi * k / n), c[1] + r * math.sin(2 * math.pi * k / n)]
            for k in range(n + 1)]


def feature(fid, coords, kind, material, thickness):
    return {"type": "Feature", "id": fid,
            "properties": {"type": kind, "material": material, "thickness": thickness},
            "geometry": {"type": "LineString",
                         "coordinates": [[round(x, 6), round(y, 6)] for x, y in coords]}}


def vineyard():
    """Rows of vines: a wire per row (unbounded) with posts every 0.1 beside it."""
    out = []
    for row in range(5):
        y = 0.1 + 0.2 * row
        out.append((line([0.0, y + 0.03], [1.0, y + 0.03]), "unbounded", "vine", 0.012))
        for k in range(10):
            out.append((ring([0.05 + 0.1 * k, y], 0.012), "bounded", "post", 0.004))
    return out


def orchard():
    """Trees (trunk + crown) in staggered rows."""
    out = []
    for row in range(4):
        y = 0.125 + 0.25 * row
        shift = 0.1 if row % 2 else 0.0
        for k in range(5):
            x = 0.1 + 0.2 * k + shift
            if x > 0.95:
                continue
            out.append((line([x, y - 0.07], [x, y - 0.02]), "bounded", "trunk", 0.01))
            out.append((ring([x, y + 0.025], 0.045), "bounded", "crown", 0.006))
    return out


def furrows():
    """Field strips: pairs of furrows with a wider gap between the pairs."""
    out = []
    for pair in range(4):
        for k in range(2):
            y = 0.08 + 0.25 * pair + 0.05 * k
            out.append((line([0.0, y], [1.0, y]), "unbounded", "furrow", 0.01))
    return out


def boulders():
    """Elongated boulders along strata: short segments in three bands, slightly tilted."""
    out = []
    for band, y in enumerate([0.2, 0.5, 0.8]):
        for k in range(6):
            x = 0.08 + 0.16 * k + (0.05 if band == 1 else 0.0)
            if x > 0.92:
                continue
            tilt = 0.1 * math.sin(3.0 * k + band)
            d = [0.04 * math.cos(tilt), 0.04 * math.sin(tilt)]
            out.append((line([x - d[0], y - d[1]], [x + d[0], y + d[1]], 4), "bounded", "rock", 0.02))
    return out


def hedge():
    """One hedge wave across the square: appears once, so it is extended, never repeated."""
    pts = [[k / 64, 0.5 + 0.12 * math.sin(2 * math.pi * 1.5 * k / 64)] for k in range(65)]
    return [(pts, "unbounded", "hedge", 0.02)]


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(__file__), "..", "samples", "sketches")
    os.makedirs(folder, exist_ok=True)
    for name, strokes in [("vineyard", vineyard()), ("orchard", orchard()),
                          ("furrows", furrows()), ("boulders", boulders()), ("hedge", hedge())]:
        collection = {"type": "FeatureCollection",
                      "features": [feature(i + 1, c, k, m, t)
                                   for i, (c, k, m, t) in enumerate(strokes)]}
        with open(os.path.join(folder, name + ".geojson"), "w") as f:
            json.dump(collection, f, indent=None, separators=(",", ":"))
            f.write("\n")


if __name__ == "__main__":
    main()
