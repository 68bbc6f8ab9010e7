#pragma once
// Reading heights between cells over any cell accessor: a whole raster, a window of one (cells
// addressed in the whole grid's indices), or a block cache. One implementation, so a windowed
// or cached read gives the same bits as the whole raster.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/grid.hpp"
#include "geo/heightfield.hpp"
#include "geo/resample.hpp"

namespace tw::detail {

// Catmull-Rom weights of the four cells at offsets -1, 0, 1, 2 for a fraction t in [0, 1).
inline std::array<double, 4> catmull_rom(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {0.5 * (-t3 + 2 * t2 - t), 0.5 * (3 * t3 - 5 * t2 + 2), 0.5 * (-3 * t3 + 4 * t2 + t),
          0.5 * (t3 - t2)};
}

// `cell(col, row)`: the height of a cell of `grid`, NaN for nodata and off the grid.
template <class Cell>
double bilinear_at(const Cell& cell, const GridSpec& grid, Vec2 world) {
  const Vec2 p = grid.world_to_pixel(world) - Vec2{0.5, 0.5};  // in pixel-centre units
  const double fx = std::floor(p.x), fy = std::floor(p.y);
  const int c = int(fx), r = int(fy);
  const double tx = p.x - fx, ty = p.y - fy;
  double sum = 0.0, weight = 0.0;
  for (int dy = 0; dy <= 1; ++dy)
    for (int dx = 0; dx <= 1; ++dx) {
      const float h = cell(c + dx, r + dy);
      if (std::isnan(h)) continue;
      const double w = (dx ? tx : 1.0 - tx) * (dy ? ty : 1.0 - ty);
      sum += w * h;
      weight += w;
    }
  return weight > 1e-9 ? sum / weight : std::numeric_limits<double>::quiet_NaN();
}

template <class Cell>
double cubic_at(const Cell& cell, const GridSpec& grid, Vec2 world) {
  const Vec2 p = grid.world_to_pixel(world) - Vec2{0.5, 0.5};
  if (p.x < 0.0 || p.y < 0.0 || p.x > grid.width - 1 || p.y > grid.height - 1)
    return bilinear_at(cell, grid, world);
  const double fx = std::floor(p.x), fy = std::floor(p.y);
  const auto wx = catmull_rom(p.x - fx), wy = catmull_rom(p.y - fy);
  double sum = 0.0;
  for (int j = 0; j < 4; ++j) {
    const int row = std::clamp(int(fy) - 1 + j, 0, grid.height - 1);
    double along = 0.0;
    for (int i = 0; i < 4; ++i) {
      const float h = cell(std::clamp(int(fx) - 1 + i, 0, grid.width - 1), row);
      if (std::isnan(h)) return bilinear_at(cell, grid, world);
      along += wx[std::size_t(i)] * h;
    }
    sum += wy[std::size_t(j)] * along;
  }
  return sum;
}

// Samples per side when a cell of `to` spans `ratio` cells of the source.
inline int samples_per_side(double ratio) {
  // Clamped in double: the ratio of an absurd resolution overflows int.
  return int(std::clamp(std::ceil(ratio - 1e-9), 1.0, double(kMaxSamplesPerSide)));
}

// Cell (col, row) of `to` read from `cell` over `from` (resample_heights' rule, see
// geo/resample.hpp); `col`, `row` are indices of the whole `to` grid.
template <class Cell>
float resampled_cell(const Cell& cell, const GridSpec& from, const GridSpec& to, int col, int row,
                     int kx, int ky, Resampling resampling) {
  // As GDAL's warper: nodata under the centre stays nodata, so holes neither fill nor shrink.
  const Vec2 p = from.world_to_pixel(to.pixel_centre_world(col, row));
  const double fc = std::floor(p.x), fr = std::floor(p.y);
  if (fc >= 0.0 && fr >= 0.0 && fc < from.width && fr < from.height &&
      std::isnan(cell(int(fc), int(fr)))) {
    return std::numeric_limits<float>::quiet_NaN();
  }
  double sum = 0.0;
  int valid = 0;
  for (int j = 0; j < ky; ++j)
    for (int i = 0; i < kx; ++i) {
      const Vec2 world = to.pixel_to_world({col + (i + 0.5) / kx, row + (j + 0.5) / ky});
      const double h = resampling == Resampling::cubic ? cubic_at(cell, from, world)
                                                       : bilinear_at(cell, from, world);
      if (std::isnan(h)) continue;
      sum += h;
      ++valid;
    }
  return valid ? float(sum / valid) : std::numeric_limits<float>::quiet_NaN();
}

}  // namespace tw::detail
