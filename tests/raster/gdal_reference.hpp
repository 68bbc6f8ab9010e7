#pragma once
// GDAL's own rasterizer (the library behind gdal_rasterize) on a MEM dataset: the reference
// that tests and the benchmark compare against.
#include <cstdint>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "raster/polygon.hpp"

namespace tw::test {

// Burns 1 where GDALRasterizeGeometries (default options: pixel-centre rule) fills the
// polygons, on the whole grid, in the given CRS (e.g. "EPSG:32633").
Raster<std::uint8_t> gdal_rasterize(const std::vector<Polygon>& polygons, const GridSpec& grid,
                                    const std::string& crs = "EPSG:32633");

// Fraction of equal pixels.
double agreement(const Raster<std::uint8_t>& a, const Raster<std::uint8_t>& b);

// The window's crop of a whole-grid raster.
template <class T>
Raster<T> crop(const Raster<T>& whole, const Window& w) {
  Raster<T> out(w.width, w.height);
  for (int r = 0; r < w.height; ++r)
    for (int c = 0; c < w.width; ++c) out.at(c, r) = whole.at(w.col0 + c, w.row0 + r);
  return out;
}

}  // namespace tw::test
