#include "raster/avoidance.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/segment_distance.hpp"
#include "raster/distance.hpp"
#include "raster/foldover.hpp"
#include "raster/footprint.hpp"
#include "raster/rasterize.hpp"

namespace tw {
namespace {

void add_mask(Raster<std::uint8_t>& forbidden, const Raster<std::uint8_t>& more) {
  for (std::size_t i = 0; i < forbidden.pixels.size(); ++i)
    forbidden.pixels[i] = std::uint8_t(forbidden.pixels[i] | (more.pixels[i] ? 1 : 0));
}

// `more` covers `part`, a sub-window of `window`, the window of `forbidden`.
void add_mask_on(Raster<std::uint8_t>& forbidden, const Window& window,
                 const Raster<std::uint8_t>& more, const Window& part) {
  for (int row = 0; row < part.height; ++row)
    for (int col = 0; col < part.width; ++col)
      if (more.at(col, row))
        forbidden.at(part.col0 - window.col0 + col, part.row0 - window.row0 + row) = 1;
}

// A ribbon's footprint and fold-overs, rasterized on the part of `window` its pieces can touch
// (not the whole window: hundreds of ribbons on a large window otherwise cost hundreds of
// whole-window passes). Window results equal crops of larger ones (raster/rasterize.hpp,
// raster/foldover.hpp), so the mask is the same.
void burn_ribbon(const Ribbon& ribbon, bool footprint, bool foldovers, const GridSpec& grid,
                 const Window& window, Raster<std::uint8_t>& forbidden) {
  const Window part = intersect(ribbon_window(ribbon, grid), window);
  if (part.width == 0) return;
  if (footprint) {
    Raster<std::uint8_t> cells;
    burn_polygons(piece_polygons(ribbon), grid, part, cells, 1);
    add_mask_on(forbidden, window, cells, part);
  }
  // Bow-tie lobes can fall outside the even-odd fill of their own quad.
  if (foldovers) add_mask_on(forbidden, window, foldover_mask(ribbon, grid, part), part);
}

// The forbidden mask of build_avoidance_map (no distance yet).
AvoidanceMap build_mask(const AvoidanceInputs& inputs, const GridSpec& grid, const Window& window) {
  if (inputs.lines.size() != inputs.line_widths.size())
    fail("avoidance map: {} lines but {} line widths", inputs.lines.size(),
         inputs.line_widths.size());
  AvoidanceMap map;
  map.grid = grid;
  map.window = window;
  map.forbidden = Raster<std::uint8_t>(window.width, window.height, 0);
  burn_polygons(inputs.polygons, grid, window, map.forbidden, 1);
  burn_polygons(inputs.junction_discs, grid, window, map.forbidden, 1);
  burn_buffered_lines(inputs.lines, inputs.line_widths, grid, window, map.forbidden, 1);
  for (std::size_t r = 0; r < inputs.ribbons.size(); ++r) {
    const Ribbon* ribbon = inputs.ribbons[r];
    if (ribbon == nullptr) fail("avoidance map: ribbon {} is null", r);
    burn_ribbon(*ribbon, true, inputs.include_foldovers, grid, window, map.forbidden);
  }
  if (inputs.current != nullptr && inputs.include_foldovers)
    burn_ribbon(*inputs.current, false, true, grid, window, map.forbidden);
  return map;
}

}  // namespace

AvoidanceMap build_avoidance_map(const AvoidanceInputs& inputs, const GridSpec& grid,
                                 const Window& window, double max_distance) {
  if (!(max_distance > 0.0))
    fail("avoidance map: max_distance must be > 0 metres, got {}", max_distance);
  if (std::isinf(max_distance)) {
    AvoidanceMap map = build_mask(inputs, grid, window);
    map.distance = distance_to_mask(map.forbidden, grid.pixel_width, grid.pixel_height);
    return map;
  }
  // Every forbidden pixel within max_distance of the window lies in the halo, so the capped
  // distance is exact: the same bits as on any larger window.
  const double pixel = std::min(grid.pixel_width, grid.pixel_height);
  const int halo = int(std::min(std::ceil(max_distance / pixel) + 1.0, 1e9));
  const Window grown = grow_window(window, halo, grid);
  const AvoidanceMap wide = build_mask(inputs, grid, grown);
  const Raster<float> distance =
      distance_to_mask(wide.forbidden, grid.pixel_width, grid.pixel_height);
  AvoidanceMap map;
  map.grid = grid;
  map.window = window;
  map.forbidden = Raster<std::uint8_t>(window.width, window.height);
  map.distance = Raster<float>(window.width, window.height);
  const float cap = float(max_distance);
  for (int row = 0; row < window.height; ++row)
    for (int col = 0; col < window.width; ++col) {
      const int c = window.col0 - grown.col0 + col, r = window.row0 - grown.row0 + row;
      map.forbidden.at(col, row) = wide.forbidden.at(c, r);
      map.distance.at(col, row) = std::min(distance.at(c, r), cap);
    }
  return map;
}

void burn_avoidance(const AvoidanceInputs& inputs, const GridSpec& grid,
                    SparseRaster<std::uint8_t>& forbidden) {
  for (const TileIndex t : forbidden.tiles()) {
    const AvoidanceMap tile = build_mask(inputs, grid, forbidden.tile_window(t));
    Raster<std::uint8_t>& cells = *forbidden.tile(t);
    add_mask(cells, tile.forbidden);
  }
}

bool segment_clear(const SparseAvoidance& a, Vec2 p, Vec2 q, double half_width) {
  const GridSpec& g = a.grid;
  const SparseRaster<std::uint8_t>& cells = a.forbidden;
  // Cells whose centre may lie within half_width of the segment.
  const double c0 =
      std::floor((std::min(p.x, q.x) - half_width - g.origin_x) / g.pixel_width - 0.5);
  const double c1 = std::ceil((std::max(p.x, q.x) + half_width - g.origin_x) / g.pixel_width - 0.5);
  const double r0 =
      std::floor((g.origin_y - std::max(p.y, q.y) - half_width) / g.pixel_height - 0.5);
  const double r1 =
      std::ceil((g.origin_y - std::min(p.y, q.y) + half_width) / g.pixel_height - 0.5);
  const int col0 = int(std::max(0.0, c0)), col1 = int(std::min(double(cells.width() - 1), c1));
  const int row0 = int(std::max(0.0, r0)), row1 = int(std::min(double(cells.height() - 1), r1));
  if (col0 > col1 || row0 > row1) return true;
  const int size = cells.tile_size();
  for (int ty = row0 / size; ty <= row1 / size; ++ty)
    for (int tx = col0 / size; tx <= col1 / size; ++tx) {
      const Raster<std::uint8_t>* tile = cells.tile({tx, ty});
      if (tile == nullptr) continue;  // nothing forbidden there
      const Window w = cells.tile_window({tx, ty});
      for (int row = std::max(row0, w.row0); row <= std::min(row1, w.row_end() - 1); ++row)
        for (int col = std::max(col0, w.col0); col <= std::min(col1, w.col_end() - 1); ++col) {
          if (!tile->at(col - w.col0, row - w.row0)) continue;
          if (distance_to_segment(g.pixel_centre_world(col, row), p, q) <= half_width) return false;
        }
    }
  return true;
}

}  // namespace tw
