#include "raster/avoidance.hpp"

#include "core/error.hpp"
#include "raster/distance.hpp"
#include "raster/foldover.hpp"
#include "raster/rasterize.hpp"

namespace tw {
namespace {

void add_mask(Raster<std::uint8_t>& forbidden, const Raster<std::uint8_t>& more) {
  for (std::size_t i = 0; i < forbidden.pixels.size(); ++i)
    forbidden.pixels[i] = std::uint8_t(forbidden.pixels[i] | (more.pixels[i] ? 1 : 0));
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
    burn_polygons(piece_polygons(*ribbon), grid, window, map.forbidden, 1);
    // Bow-tie lobes can fall outside the even-odd fill of their own quad.
    if (inputs.include_foldovers) add_mask(map.forbidden, foldover_mask(*ribbon, grid, window));
  }
  if (inputs.current != nullptr && inputs.include_foldovers)
    add_mask(map.forbidden, foldover_mask(*inputs.current, grid, window));
  return map;
}

}  // namespace

AvoidanceMap build_avoidance_map(const AvoidanceInputs& inputs, const GridSpec& grid,
                                 const Window& window) {
  AvoidanceMap map = build_mask(inputs, grid, window);
  map.distance = distance_to_mask(map.forbidden, grid.pixel_width, grid.pixel_height);
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

}  // namespace tw
