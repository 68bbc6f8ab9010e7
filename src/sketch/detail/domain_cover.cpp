#include "sketch/detail/domain_cover.hpp"

#include <algorithm>
#include <cmath>

#include "raster/rasterize.hpp"

namespace tw::detail {

DomainCover::DomainCover(const Polygon& domain, double cell) {
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (const Ring& ring : domain)
    for (Vec2 p : ring) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
  const double box = (hi.x - lo.x) * (hi.y - lo.y);
  cell = std::max({cell, std::sqrt(box / kMaxCells), 1e-6 * std::max(hi.x - lo.x, hi.y - lo.y)});
  grid_.pixel_width = grid_.pixel_height = cell;
  grid_.origin_x = lo.x - cell;
  grid_.origin_y = hi.y + cell;
  grid_.width = int(std::ceil((hi.x - lo.x) / cell)) + 2;
  grid_.height = int(std::ceil((hi.y - lo.y) / cell)) + 2;
  Raster<std::uint8_t> cells;
  burn_polygons({domain}, grid_, Window::whole(grid_), cells, inside);
  states_ = std::move(cells.pixels);
  // Every cell an edge passes through, and their neighbours: samples a quarter cell apart stay
  // within one cell of every point of the edge between them.
  for (const Ring& ring : domain)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
      const int n = std::max(1, int(std::ceil(4.0 * distance(a, b) / cell)));
      for (int k = 0; k <= n; ++k) {
        const Vec2 px = grid_.world_to_pixel(lerp(a, b, double(k) / n));
        const int col = int(std::floor(px.x)), row = int(std::floor(px.y));
        for (int r = std::max(0, row - 1); r <= std::min(grid_.height - 1, row + 1); ++r)
          for (int c = std::max(0, col - 1); c <= std::min(grid_.width - 1, col + 1); ++c)
            states_[std::size_t(r) * grid_.width + c] = boundary;
      }
    }
}

DomainCover::State DomainCover::state(int col, int row) const {
  if (col < 0 || row < 0 || col >= grid_.width || row >= grid_.height) return outside;
  return State(states_[std::size_t(row) * grid_.width + col]);
}

bool DomainCover::near(Vec2 p, double reach) const {
  const Vec2 px = grid_.world_to_pixel(p);
  const double r = std::ceil(reach / cell()) + 1.0;
  // In double first: a point far off the lattice must not overflow an int.
  const double c0 = std::max(0.0, std::floor(px.x) - r),
               c1 = std::min(grid_.width - 1.0, std::floor(px.x) + r);
  const double r0 = std::max(0.0, std::floor(px.y) - r),
               r1 = std::min(grid_.height - 1.0, std::floor(px.y) + r);
  if (r0 > r1 || c0 > c1) return false;
  for (int row = int(r0); row <= int(r1); ++row)
    for (int col = int(c0); col <= int(c1); ++col)
      if (state(col, row) != outside) return true;
  return false;
}

std::optional<bool> DomainCover::contains(const std::array<Vec2, 4>& corners) const {
  double c0 = INFINITY, c1 = -INFINITY, r0 = INFINITY, r1 = -INFINITY;
  Vec2 centre;
  for (Vec2 p : corners) {
    const Vec2 px = grid_.world_to_pixel(p);
    c0 = std::min(c0, px.x), c1 = std::max(c1, px.x), r0 = std::min(r0, px.y),
    r1 = std::max(r1, px.y);
    centre += p * 0.25;
  }
  if (c0 < 0.0 || r0 < 0.0 || c1 >= grid_.width || r1 >= grid_.height) return false;
  const Vec2 middle = grid_.world_to_pixel(centre);
  if (state(int(std::floor(middle.x)), int(std::floor(middle.y))) == outside) return false;
  for (int row = int(std::floor(r0)); row <= int(std::floor(r1)); ++row)
    for (int col = int(std::floor(c0)); col <= int(std::floor(c1)); ++col)
      if (state(col, row) != inside) return std::nullopt;
  return true;
}

}  // namespace tw::detail
