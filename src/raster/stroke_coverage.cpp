#include "raster/stroke_coverage.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/segment_distance.hpp"

namespace tw {

Raster<float> stroke_coverage(const std::vector<const std::vector<Vec2>*>& lines,
                              const std::vector<double>& widths, const GridSpec& grid,
                              const Window& window) {
  if (widths.size() != lines.size())
    fail("stroke_coverage: {} widths for {} lines", widths.size(), lines.size());
  Raster<float> out(window.width, window.height, 0.0f);
  const double p = 0.5 * (grid.pixel_width + grid.pixel_height);
  for (std::size_t l = 0; l < lines.size(); ++l) {
    const double w = widths[l];
    if (!(w >= 0.0) || !std::isfinite(w)) fail("stroke_coverage: line {}: width {}", l, w);
    const std::vector<Vec2>& line = *lines[l];
    const double reach = 0.5 * (w + p);  // beyond it the band misses the pixel
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const Vec2 a = line[i], b = line[i + 1];
      const Vec2 lo = grid.world_to_pixel({std::min(a.x, b.x) - reach, std::max(a.y, b.y) + reach});
      const Vec2 hi = grid.world_to_pixel({std::max(a.x, b.x) + reach, std::min(a.y, b.y) - reach});
      const int c0 = std::max(window.col0, int(std::floor(std::max(lo.x, -1e9))));
      const int r0 = std::max(window.row0, int(std::floor(std::max(lo.y, -1e9))));
      const int c1 = std::min(window.col0 + window.width, int(std::ceil(std::min(hi.x, 1e9))));
      const int r1 = std::min(window.row0 + window.height, int(std::ceil(std::min(hi.y, 1e9))));
      for (int row = r0; row < r1; ++row)
        for (int col = c0; col < c1; ++col) {
          const double d = distance_to_segment(grid.pixel_centre_world(col, row), a, b);
          const double overlap = std::min(d + 0.5 * w, 0.5 * p) - std::max(d - 0.5 * w, -0.5 * p);
          if (overlap <= 0.0) continue;
          float& v = out.at(col - window.col0, row - window.row0);
          v = std::max(v, float(std::min(1.0, overlap / p)));
        }
    }
  }
  return out;
}

}  // namespace tw
