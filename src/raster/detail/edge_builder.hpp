#pragma once
// World shapes to scanline edges in (supersampled) pixel space of the world grid, culling
// shapes whose box misses the window: on a tile of a large world most shapes are elsewhere.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/grid.hpp"
#include "raster/detail/scanline.hpp"

namespace tw::detail {

class EdgeBuilder {
 public:
  // `window` is in the scaled pixel space (a window of the grid times `scale`).
  EdgeBuilder(const GridSpec& grid, double scale, const Window& window)
      : grid_(grid), scale_(scale), window_(window) {}

  // Adds the edges of one shape (a range of rings, each a range of world points, closed
  // implicitly) filled even-odd as `shape`. Returns false when a point is not finite.
  template <class Rings>
  bool add_shape(const Rings& rings, std::uint32_t shape) {
    double min_x = INFINITY, max_x = -INFINITY, min_y = INFINITY, max_y = -INFINITY;
    for (const auto& ring : rings)
      for (const Vec2 w : ring) {
        if (!is_finite(w)) return false;
        min_x = std::min(min_x, w.x);
        max_x = std::max(max_x, w.x);
        min_y = std::min(min_y, w.y);
        max_y = std::max(max_y, w.y);
      }
    const Vec2 top_left = to_pixel({min_x, max_y}), bottom_right = to_pixel({max_x, min_y});
    // A centre c + 0.5 inside the box needs c in [min - 0.5, max - 0.5]; keep a pixel of slack.
    if (bottom_right.x < window_.col0 - 1.0 || top_left.x > window_.col_end() + 1.0 ||
        bottom_right.y < window_.row0 - 1.0 || top_left.y > window_.row_end() + 1.0)
      return true;
    for (const auto& ring : rings) {
      const auto n = std::size(ring);
      if (n < 2) continue;
      auto it = std::begin(ring);
      const Vec2 first = to_pixel(*it);
      Vec2 previous = first;
      for (++it; it != std::end(ring); ++it) {
        const Vec2 current = to_pixel(*it);
        add_edge(previous, current, shape);
        previous = current;
      }
      add_edge(previous, first, shape);
    }
    return true;
  }

  std::vector<ScanEdge> edges;

 private:
  Vec2 to_pixel(Vec2 w) const { return grid_.world_to_pixel(w) * scale_; }
  void add_edge(Vec2 a, Vec2 b, std::uint32_t shape) {
    if (a.y == b.y) return;  // horizontal edges cross no row centre
    if (a.y > b.y) std::swap(a, b);
    ScanEdge e;
    e.x_top = a.x;
    e.y_top = a.y;
    e.dx_dy = (b.x - a.x) / (b.y - a.y);
    e.row_begin = first_row_at_or_below(a.y);
    e.row_end = first_row_at_or_below(b.y);
    e.shape = shape;
    if (e.row_begin < e.row_end) edges.push_back(e);
  }

  GridSpec grid_;
  double scale_;
  Window window_;
};

}  // namespace tw::detail
