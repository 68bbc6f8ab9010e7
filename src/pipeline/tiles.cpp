// The tile grid and the heights a tile reads (pipeline/plan.hpp).
#include <algorithm>

#include "core/error.hpp"
#include "pipeline/plan.hpp"
#include "raster/footprint.hpp"

namespace tw {

std::vector<TileSpec> tile_grid(const GridSpec& grid, int size, int overlap) {
  return tile_grid(grid, Window::whole(grid), size, overlap);
}

std::vector<TileSpec> tile_grid(const GridSpec& grid, const Window& area, int size, int overlap) {
  if (size < 0) fail("output.tiles.size: must be >= 0 pixels, got {}", size);
  if (overlap < 0) fail("output.tiles.overlap: must be >= 0 pixels, got {}", overlap);
  if (size == 0 && overlap > 0) fail("output.tiles.overlap: {} pixels without tiles", overlap);
  if (grid.width <= 0 || grid.height <= 0) fail("tile_grid: the grid is empty");
  if (area.width <= 0 || area.height <= 0 || intersect(area, Window::whole(grid)) != area)
    fail("tile_grid: the area is not a window of the grid");
  if (size == 0) return {TileSpec{0, 0, 0, area, area}};
  const int columns = (area.width + size - 1) / size;
  const int rows = (area.height + size - 1) / size;
  std::vector<TileSpec> tiles;
  tiles.reserve(std::size_t(columns) * rows);
  for (int iy = 0; iy < rows; ++iy)
    for (int ix = 0; ix < columns; ++ix) {
      TileSpec& t = tiles.emplace_back();
      t.index = iy * columns + ix;
      t.ix = ix;
      t.iy = iy;
      t.window = intersect({area.col0 + ix * size, area.row0 + iy * size, size, size}, area);
      t.halo_window = intersect(grow_window(t.window, overlap, grid), area);
    }
  return tiles;
}

GridSpec window_grid(const GridSpec& grid, const Window& window) {
  const Vec2 corner = grid.pixel_to_world({double(window.col0), double(window.row0)});
  return {window.width, window.height, corner.x, corner.y, grid.pixel_width, grid.pixel_height};
}

std::string tile_file_stem(const std::string& layer, const TileSpec& tile) {
  return fmt::format("{}_x{}_y{}", layer, tile.ix, tile.iy);
}

Raster<float> read_height_window(const HeightSource& source, const GridSpec& grid,
                                 const Window& window) {
  if (intersect(window, Window::whole(grid)) != window || window.width == 0)
    fail("{}: window ({}, {}, {} x {}) is not inside the {} x {} grid", source.source, window.col0,
         window.row0, window.width, window.height, grid.width, grid.height);
  if (source.reader) return source.reader->read(window);
  if (source.generated) return open_generated_heightfield(*source.generated)->read(window);
  if (!source.heights) fail("{}: the plan holds no heights", source.source);
  const Raster<float>& whole = *source.heights;
  Raster<float> out(window.width, window.height);
  for (int row = 0; row < window.height; ++row) {
    const float* from = &whole.at(window.col0, window.row0 + row);
    std::copy(from, from + window.width, &out.at(0, row));
  }
  return out;
}

}  // namespace tw
