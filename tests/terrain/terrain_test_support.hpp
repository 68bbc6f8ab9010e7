#pragma once
// Small synthetic grids and features for the terrain tests.
#include <cmath>
#include <functional>

#include "core/grid.hpp"
#include "terrain/features.hpp"

namespace tw::test {

// A size x size grid of 1 m pixels whose top-left corner is world (0, size).
inline GridSpec unit_grid(int size) {
  return GridSpec{size, size, 0.0, double(size), 1.0, 1.0};
}

// Heights from a function of world (x, y) at pixel centres.
inline Raster<float> heights_from(const GridSpec& grid,
                                  const std::function<double(double, double)>& f) {
  Raster<float> r(grid.width, grid.height);
  for (int row = 0; row < grid.height; ++row)
    for (int col = 0; col < grid.width; ++col) {
      const Vec2 p = grid.pixel_centre_world(col, row);
      r.at(col, row) = float(f(p.x, p.y));
    }
  return r;
}

inline TerrainFeature feature(FeatureKind kind, std::int64_t fid, std::vector<Vec2> points,
                              double width) {
  TerrainFeature f;
  f.kind = kind;
  f.fid = fid;
  f.centerline.points = std::move(points);
  f.width = width;
  return f;
}

}  // namespace tw::test
