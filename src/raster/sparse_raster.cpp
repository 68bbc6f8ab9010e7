#include "raster/sparse_raster.hpp"

#include <cmath>

#include "raster/footprint.hpp"
#include "raster/rasterize.hpp"

namespace tw {

std::vector<TileIndex> ribbon_tiles(const Ribbon& ribbon, const GridSpec& grid, int tile_size,
                                    int halo) {
  if (grid.width <= 0 || grid.height <= 0) return {};
  if (tile_size <= 0) tile_size = std::max(grid.width, grid.height);
  const int tiles_x = (grid.width + tile_size - 1) / tile_size;
  const int tiles_y = (grid.height + tile_size - 1) / tile_size;
  std::vector<std::uint8_t> met(std::size_t(tiles_x) * tiles_y, 0);
  for (const Piece& piece : ribbon.pieces) {
    const PieceBox box = piece_pixel_box(piece, grid);
    const double min_x = box.lo.x, min_y = box.lo.y, max_x = box.hi.x, max_y = box.hi.y;
    if (!(std::isfinite(min_x) && std::isfinite(max_x) && std::isfinite(min_y) &&
          std::isfinite(max_y)))
      continue;
    // In double first: a corner far off the grid must not overflow an int.
    const double c0 = std::floor(min_x) - halo, c1 = std::floor(max_x) + halo;
    const double r0 = std::floor(min_y) - halo, r1 = std::floor(max_y) + halo;
    if (c1 < 0 || r1 < 0 || c0 >= grid.width || r0 >= grid.height) continue;
    const int tx0 = int(std::max(0.0, c0)) / tile_size;
    const int tx1 = int(std::min(double(grid.width - 1), c1)) / tile_size;
    const int ty0 = int(std::max(0.0, r0)) / tile_size;
    const int ty1 = int(std::min(double(grid.height - 1), r1)) / tile_size;
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) met[std::size_t(ty) * tiles_x + tx] = 1;
  }
  std::vector<TileIndex> tiles;
  for (int ty = 0; ty < tiles_y; ++ty)
    for (int tx = 0; tx < tiles_x; ++tx)
      if (met[std::size_t(ty) * tiles_x + tx]) tiles.push_back({tx, ty});
  return tiles;
}

void add_on_lattice(const SparseRaster<std::uint8_t>& source, const GridSpec& source_grid,
                    SparseRaster<std::uint8_t>& target, const GridSpec& target_grid) {
  const int dc =
      int(std::lround((source_grid.origin_x - target_grid.origin_x) / target_grid.pixel_width));
  const int dr =
      int(std::lround((target_grid.origin_y - source_grid.origin_y) / target_grid.pixel_height));
  const int size = target.tile_size();
  for (const TileIndex s : source.tiles()) {
    const Window from = source.tile_window(s);
    const Raster<std::uint8_t>& cells = *source.tile(s);
    // The source tile in target cells, clipped to the target.
    const int col0 = std::max(0, from.col0 + dc),
              col1 = std::min(target.width(), from.col_end() + dc);
    const int row0 = std::max(0, from.row0 + dr),
              row1 = std::min(target.height(), from.row_end() + dr);
    if (col0 >= col1 || row0 >= row1) continue;
    for (int ty = row0 / size; ty <= (row1 - 1) / size; ++ty) {
      for (int tx = col0 / size; tx <= (col1 - 1) / size; ++tx) {
        Raster<std::uint8_t>* to = target.tile({tx, ty});
        if (to == nullptr) continue;
        const Window w = target.tile_window({tx, ty});
        for (int row = std::max(row0, w.row0); row < std::min(row1, w.row_end()); ++row)
          for (int col = std::max(col0, w.col0); col < std::min(col1, w.col_end()); ++col)
            if (cells.at(col - dc - from.col0, row - dr - from.row0))
              to->at(col - w.col0, row - w.row0) = 1;
      }
    }
  }
}

void burn_buffered_lines_on(const std::vector<const std::vector<Vec2>*>& lines,
                            const std::vector<double>& widths, const GridSpec& grid,
                            SparseRaster<std::uint8_t>& target, std::uint8_t value) {
  const int size = target.tile_size();
  // Per allocated tile (by slot in target.tiles()), the lines whose buffered box meets it.
  std::vector<std::int32_t> slot(std::size_t(target.tiles_x()) * target.tiles_y(), -1);
  for (std::size_t k = 0; k < target.tiles().size(); ++k)
    slot[std::size_t(target.tiles()[k].ty) * target.tiles_x() + target.tiles()[k].tx] =
        std::int32_t(k);
  std::vector<std::vector<std::size_t>> met(target.tiles().size());
  for (std::size_t l = 0; l < lines.size(); ++l) {
    if (lines[l]->empty()) continue;
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (const Vec2 p : *lines[l])
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y),
      y1 = std::max(y1, p.y);
    const double r = 0.5 * widths[l];
    // In double first: a line far off the canvas must not overflow an int.
    const double c0 = std::floor((x0 - r - grid.origin_x) / grid.pixel_width) - 1;
    const double c1 = std::floor((x1 + r - grid.origin_x) / grid.pixel_width) + 1;
    const double r0 = std::floor((grid.origin_y - y1 - r) / grid.pixel_height) - 1;
    const double r1 = std::floor((grid.origin_y - y0 + r) / grid.pixel_height) + 1;
    if (!(c1 >= 0 && r1 >= 0 && c0 < target.width() && r0 < target.height())) continue;
    const int tx0 = int(std::max(0.0, c0)) / size;
    const int tx1 = int(std::min(double(target.width() - 1), c1)) / size;
    const int ty0 = int(std::max(0.0, r0)) / size;
    const int ty1 = int(std::min(double(target.height() - 1), r1)) / size;
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx)
        if (const std::int32_t s = slot[std::size_t(ty) * target.tiles_x() + tx]; s >= 0)
          met[std::size_t(s)].push_back(l);
  }
  for (std::size_t k = 0; k < met.size(); ++k) {
    if (met[k].empty()) continue;
    std::vector<std::vector<Vec2>> some;
    std::vector<double> some_widths;
    for (const std::size_t l : met[k]) some.push_back(*lines[l]), some_widths.push_back(widths[l]);
    const TileIndex t = target.tiles()[k];
    burn_buffered_lines(some, some_widths, grid, target.tile_window(t), *target.tile(t), value);
  }
}

}  // namespace tw
