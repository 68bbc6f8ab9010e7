#include "terrain/trench.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geo/resample.hpp"

namespace tw {

namespace {

// The lowest valid cell of `height` whose centre lies within `radius` of `world` (NaN: none).
double lowest_within(const Raster<float>& height, const GridSpec& grid, Vec2 world, double radius) {
  const Vec2 p = grid.world_to_pixel(world);
  const int c0 = std::max(0, int(std::floor(p.x - radius / grid.pixel_width)));
  const int c1 = std::min(grid.width - 1, int(std::floor(p.x + radius / grid.pixel_width)));
  const int r0 = std::max(0, int(std::floor(p.y - radius / grid.pixel_height)));
  const int r1 = std::min(grid.height - 1, int(std::floor(p.y + radius / grid.pixel_height)));
  double lowest = std::numeric_limits<double>::quiet_NaN();
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      const Vec2 centre = grid.pixel_centre_world(c, r);
      if (std::hypot(centre.x - world.x, centre.y - world.y) > radius) continue;
      const float h = height.at(c, r);
      if (std::isfinite(h) && !(h >= lowest)) lowest = h;
    }
  }
  return lowest;
}

}  // namespace

TrenchProfile trench_below_valley_floor(const Raster<float>& before, const Raster<float>& after,
                                        const GridSpec& grid, const Curve& centerline,
                                        double floor_radius, double threshold) {
  TrenchProfile out;
  const std::vector<double> cumulative = cumulative_lengths(centerline);
  if (cumulative.empty()) return out;
  const double step = 0.5 * std::min(grid.pixel_width, grid.pixel_height);
  // Half a cell's radius at least, so the cell under the line is always part of the floor.
  const double radius = std::max(floor_radius, step);
  const double total = cumulative.back();
  for (double s = 0.5 * step; s < total; s += step) {
    const Vec2 p = point_at(centerline, cumulative, s);
    const double floor = lowest_within(before, grid, p, radius);
    const double bed = sample_height_bilinear(after, grid, p);
    if (!std::isfinite(floor) || !std::isfinite(bed)) continue;
    const double trench = floor - bed;
    out.length += step;
    if (trench > threshold) out.deeper_length += step;
    out.deepest = std::max(out.deepest, trench);
  }
  return out;
}

}  // namespace tw
