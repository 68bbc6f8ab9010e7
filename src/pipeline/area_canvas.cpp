#include "pipeline/area_canvas.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/grid_limits.hpp"
#include "raster/rasterize.hpp"

namespace tw {

namespace {

struct Box {
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
};

Box box_of(const Polygon& polygon) {
  Box b;
  for (Vec2 p : polygon.front()) {
    b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y)};
    b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y)};
  }
  return b;
}

double perimeter_of(const Polygon& polygon) {
  double length = 0.0;
  for (const Ring& ring : polygon)
    for (std::size_t i = 0; i < ring.size(); ++i)
      length += distance(ring[i], ring[(i + 1) % ring.size()]);
  return length;
}

// The canvas's grid: the box grown by `margin`, edges on multiples of `cell`.
GridSpec canvas_grid(const Box& b, double cell, double margin, double& columns, double& rows) {
  GridSpec g;
  g.pixel_width = g.pixel_height = cell;
  g.origin_x = std::floor((b.lo.x - margin) / cell) * cell;
  g.origin_y = std::ceil((b.hi.y + margin) / cell) * cell;
  columns = std::ceil((b.hi.x + margin - g.origin_x) / cell);
  rows = std::ceil((g.origin_y - (b.lo.y - margin)) / cell);
  return g;
}

std::string gib(double bytes) {
  return fmt::format("{:.2f} GiB", bytes / double(std::int64_t(1) << 30));
}

}  // namespace

void require_area_memory(const SupportHierarchy& hierarchy, const Polygon& polygon,
                         const AreaSynthesisParams& params, const double cell, double margin,
                         const std::string& label) {
  const double area = polygon_area(polygon);
  const AreaEstimate shapes = estimate_area(hierarchy, polygon, params, cell);
  double canvas_cells = 0.0, directory = 0.0;
  if (cell > 0.0) {
    const Box b = box_of(polygon);
    double columns = 0.0, rows = 0.0;
    canvas_grid(b, cell, margin, columns, rows);
    const double tile = kAreaCanvasTile * cell;
    // The polygon, and the tiles along its boundary (a band a tile and the margin wide).
    canvas_cells = (area + perimeter_of(polygon) * 2.0 * (tile + margin)) / (cell * cell);
    canvas_cells = std::min(canvas_cells, columns * rows);
    directory = columns * rows / (double(kAreaCanvasTile) * kAreaCanvasTile);
    if (columns > std::numeric_limits<int>::max() || rows > std::numeric_limits<int>::max())
      directory = std::numeric_limits<double>::infinity();
  }
  // A mask byte and a check byte per canvas cell; the tile directory and its tile lattice.
  const double bytes = shapes.bytes + 2.0 * canvas_cells + 5.0 * directory;
  const double budget = memory_budget_bytes();
  if (bytes <= budget) return;
  fail(
      "{}: the polygon ({:.3g} km²) at scale {} m{} would need about {} ({:.3g} shapes{}), more "
      "than the {} allowed (3/4 of this machine's memory); raise `scale`{}, or split the polygon",
      label, area / 1e6, params.scale,
      cell > 0.0 ? fmt::format(" on {} m cells", cell) : std::string(), gib(bytes), shapes.shapes,
      cell > 0.0 ? fmt::format(", {:.3g} canvas cells", canvas_cells) : std::string(), gib(budget),
      cell > 0.0 ? " or the cell size" : "");
}

AreaCanvas area_canvas(const Polygon& polygon, double cell, double margin) {
  const Box b = box_of(polygon);
  double columns = 0.0, rows = 0.0;
  AreaCanvas canvas;
  canvas.grid = canvas_grid(b, cell, margin, columns, rows);
  canvas.grid.width = int(columns), canvas.grid.height = int(rows);
  canvas.forbidden =
      SparseRaster<std::uint8_t>(canvas.grid.width, canvas.grid.height, 0, kAreaCanvasTile);
  // The tile lattice: a tile is met when its centre lies in the polygon, or when the boundary
  // (grown by the margin) passes through it.
  GridSpec tiles = canvas.grid;
  tiles.pixel_width = tiles.pixel_height = kAreaCanvasTile * cell;
  tiles.width = canvas.forbidden.tiles_x(), tiles.height = canvas.forbidden.tiles_y();
  Raster<std::uint8_t> met;
  burn_polygons({polygon}, tiles, Window::whole(tiles), met, 1);
  // Boundary samples a quarter tile apart: every point of the boundary lies within an eighth of
  // a tile of one, so the tiles within margin + a quarter tile of the samples hold its band.
  const double tile = tiles.pixel_width, reach = (margin + 0.25 * tile) / tile;
  for (const Ring& ring : polygon)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Vec2 a = ring[i], c = ring[(i + 1) % ring.size()];
      const int n = std::max(1, int(std::ceil(4.0 * distance(a, c) / tile)));
      for (int k = 0; k <= n; ++k) {
        const Vec2 px = tiles.world_to_pixel(lerp(a, c, double(k) / n));
        const int c0 = std::max(0, int(std::floor(px.x - reach)));
        const int c1 = std::min(tiles.width - 1, int(std::floor(px.x + reach)));
        const int r0 = std::max(0, int(std::floor(px.y - reach)));
        const int r1 = std::min(tiles.height - 1, int(std::floor(px.y + reach)));
        for (int r = r0; r <= r1; ++r)
          for (int q = c0; q <= c1; ++q) met.at(q, r) = 1;
      }
    }
  for (int ty = 0; ty < tiles.height; ++ty)
    for (int tx = 0; tx < tiles.width; ++tx)
      if (met.at(tx, ty)) canvas.forbidden.add_tile({tx, ty});
  for (const TileIndex t : canvas.forbidden.tiles()) {
    const Window w = canvas.forbidden.tile_window(t);
    canvas.allocated_cells += std::int64_t(w.width) * w.height;
  }
  return canvas;
}

SparseAvoidance finish_canvas(AreaCanvas&& canvas) {
  canvas.forbidden.drop_background_tiles();
  return {canvas.grid, std::move(canvas.forbidden)};
}

std::int64_t forbidden_touched(const AreaPattern& pattern, const SparseAvoidance& avoidance) {
  const SparseRaster<std::uint8_t>& forbidden = avoidance.forbidden;
  SparseRaster<std::uint8_t> touched(forbidden.width(), forbidden.height(), 0,
                                     forbidden.tile_size());
  add_tiles(touched, forbidden.tiles());
  std::vector<const std::vector<Vec2>*> lines;
  std::vector<double> widths;
  for (const PlacedStroke& s : pattern.strokes)
    lines.push_back(&s.points), widths.push_back(s.width);
  burn_buffered_lines_on(lines, widths, avoidance.grid, touched, 1);
  std::int64_t count = 0;
  for (const TileIndex t : forbidden.tiles()) {
    const auto& a = forbidden.tile(t)->pixels;
    const auto& b = touched.tile(t)->pixels;
    for (std::size_t i = 0; i < a.size(); ++i) count += a[i] && b[i];
  }
  return count;
}

}  // namespace tw
