#include "raster/detail/window_raster.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace tw::detail {

void check_window(const Window& window, const char* who) {
  if (window.width < 0 || window.height < 0)
    fail("{}: window {}x{} has a negative size", who, window.width, window.height);
}

void prepare_window_raster(Raster<std::uint8_t>& out, const Window& window, const char* who) {
  check_window(window, who);
  if (out.pixels.empty() && out.width == 0 && out.height == 0) {
    out = Raster<std::uint8_t>(window.width, window.height, 0);
    return;
  }
  if (out.width != window.width || out.height != window.height ||
      out.pixels.size() != std::size_t(window.width) * window.height)
    fail("{}: output raster is {}x{} but the window is {}x{}", who, out.width, out.height,
         window.width, window.height);
}

std::vector<PixelRing> polygons_to_pixels(const std::vector<Polygon>& polygons,
                                          const GridSpec& grid, double scale,
                                          const Window& window) {
  std::vector<PixelRing> rings;
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    const std::size_t first = rings.size();
    double min_x = INFINITY, max_x = -INFINITY, min_y = INFINITY, max_y = -INFINITY;
    for (std::size_t r = 0; r < polygons[p].size(); ++r) {
      PixelRing ring{{}, std::uint32_t(p)};
      ring.points.reserve(polygons[p][r].size());
      for (const Vec2 w : polygons[p][r]) {
        if (!is_finite(w)) fail("polygon {} ring {}: point ({}, {}) is not finite", p, r, w.x, w.y);
        const Vec2 px = grid.world_to_pixel(w) * scale;
        min_x = std::min(min_x, px.x);
        max_x = std::max(max_x, px.x);
        min_y = std::min(min_y, px.y);
        max_y = std::max(max_y, px.y);
        ring.points.push_back(px);
      }
      rings.push_back(std::move(ring));
    }
    // A pixel centre c + 0.5 inside the box needs c in [min - 0.5, max - 0.5].
    const bool misses = max_x < window.col0 - 0.5 || min_x > window.col_end() + 0.5 ||
                        max_y < window.row0 - 0.5 || min_y > window.row_end() + 0.5;
    if (misses) rings.resize(first);
  }
  return rings;
}

}  // namespace tw::detail
