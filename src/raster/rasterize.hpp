#pragma once
// World polygons and lines onto a window of a grid, with the pixel-centre rule: a pixel is inside
// when its centre is (GDAL's gdal_rasterize default, without ALL_TOUCHED). Results depend only on
// the world grid, never on the window, so tiles are seamless: the window's result equals the crop
// of the whole grid's result. Parallel over rows (TBB), deterministic.
#include <cstdint>
#include <vector>

#include "core/grid.hpp"
#include "raster/polygon.hpp"

namespace tw {

// Sets `value` on every pixel of the window whose centre lies in one of the polygons (even-odd
// within a polygon, union across polygons). `out` covers the window: if it is empty it is
// allocated (zeros) with the window's size; any other size throws tw::Error. Pixels outside the
// polygons are left as they are, so several calls compose a union.
void burn_polygons(const std::vector<Polygon>& polygons, const GridSpec& grid, const Window& window,
                   Raster<std::uint8_t>& out, std::uint8_t value);

// Anti-aliased coverage of the union of the polygons: the fraction in [0, 1] of a
// supersample x supersample grid of sub-pixel centres inside a polygon (1..16; throws otherwise).
// Window-sized.
Raster<float> polygon_coverage(const std::vector<Polygon>& polygons, const GridSpec& grid,
                               const Window& window, int supersample = 4);

// Sets `value` where a pixel centre lies within widths_m[i] / 2 metres of polyline lines[i]
// (round caps and joins: the exact buffer). One width per line (throws tw::Error naming the line
// otherwise, or for a width < 0 / not finite). `out` as for burn_polygons.
void burn_buffered_lines(const std::vector<std::vector<Vec2>>& lines,
                         const std::vector<double>& widths_m, const GridSpec& grid,
                         const Window& window, Raster<std::uint8_t>& out, std::uint8_t value);

}  // namespace tw
