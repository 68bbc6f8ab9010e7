#include "geo/resample.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace tw {
namespace {

// Catmull-Rom weights of the four cells at offsets -1, 0, 1, 2 for a fraction t in [0, 1).
std::array<double, 4> catmull_rom(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {0.5 * (-t3 + 2 * t2 - t), 0.5 * (3 * t3 - 5 * t2 + 2), 0.5 * (-3 * t3 + 4 * t2 + t),
          0.5 * (t3 - t2)};
}

}  // namespace

double sample_height_bilinear(const Raster<float>& height, const GridSpec& grid, Vec2 world) {
  const Vec2 p = grid.world_to_pixel(world) - Vec2{0.5, 0.5};  // in pixel-centre units
  const double fx = std::floor(p.x), fy = std::floor(p.y);
  const int c = int(fx), r = int(fy);
  const double tx = p.x - fx, ty = p.y - fy;
  double sum = 0.0, weight = 0.0;
  for (int dy = 0; dy <= 1; ++dy)
    for (int dx = 0; dx <= 1; ++dx) {
      const int col = c + dx, row = r + dy;
      if (!height.inside(col, row)) continue;
      const float h = height.at(col, row);
      if (std::isnan(h)) continue;
      const double w = (dx ? tx : 1.0 - tx) * (dy ? ty : 1.0 - ty);
      sum += w * h;
      weight += w;
    }
  return weight > 1e-9 ? sum / weight : std::numeric_limits<double>::quiet_NaN();
}

double sample_height_cubic(const Raster<float>& height, const GridSpec& grid, Vec2 world) {
  const Vec2 p = grid.world_to_pixel(world) - Vec2{0.5, 0.5};
  if (p.x < 0.0 || p.y < 0.0 || p.x > height.width - 1 || p.y > height.height - 1)
    return sample_height_bilinear(height, grid, world);
  const double fx = std::floor(p.x), fy = std::floor(p.y);
  const auto wx = catmull_rom(p.x - fx), wy = catmull_rom(p.y - fy);
  double sum = 0.0;
  for (int j = 0; j < 4; ++j) {
    const int row = std::clamp(int(fy) - 1 + j, 0, height.height - 1);
    double along = 0.0;
    for (int i = 0; i < 4; ++i) {
      const float h = height.at(std::clamp(int(fx) - 1 + i, 0, height.width - 1), row);
      if (std::isnan(h)) return sample_height_bilinear(height, grid, world);
      along += wx[std::size_t(i)] * h;
    }
    sum += wy[std::size_t(j)] * along;
  }
  return sum;
}

Raster<float> resample_heights(const Raster<float>& height, const GridSpec& from,
                               const GridSpec& to, Resampling resampling) {
  // A target cell larger than the source cells averages the interpolant over k x k points (the
  // source cell centres when the lattices align), so downsampling does not alias.
  // Clamped in double: the ratio of an absurd resolution overflows int.
  const auto samples = [](double ratio) {
    return int(std::clamp(std::ceil(ratio - 1e-9), 1.0, double(kMaxSamplesPerSide)));
  };
  const int kx = samples(to.pixel_width / from.pixel_width);
  const int ky = samples(to.pixel_height / from.pixel_height);
  auto sample = [&](Vec2 world) {
    return resampling == Resampling::cubic ? sample_height_cubic(height, from, world)
                                           : sample_height_bilinear(height, from, world);
  };
  Raster<float> out(to.width, to.height);
  tbb::parallel_for(0, to.height, [&](int row) {
    for (int col = 0; col < to.width; ++col) {
      // As GDAL's warper: nodata under the centre stays nodata, so holes neither fill nor shrink.
      const Vec2 p = from.world_to_pixel(to.pixel_centre_world(col, row));
      const int c = int(std::floor(p.x)), r = int(std::floor(p.y));
      if (height.inside(c, r) && std::isnan(height.at(c, r))) {
        out.at(col, row) = std::numeric_limits<float>::quiet_NaN();
        continue;
      }
      double sum = 0.0;
      int valid = 0;
      for (int j = 0; j < ky; ++j)
        for (int i = 0; i < kx; ++i) {
          const double h = sample(to.pixel_to_world({col + (i + 0.5) / kx, row + (j + 0.5) / ky}));
          if (std::isnan(h)) continue;
          sum += h;
          ++valid;
        }
      out.at(col, row) = valid ? float(sum / valid) : std::numeric_limits<float>::quiet_NaN();
    }
  });
  return out;
}

}  // namespace tw
