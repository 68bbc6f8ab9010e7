#include "synth/detail/foldover.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/error.hpp"
#include "synth/detail/footprint.hpp"

namespace tw::detail {

SparseRaster<std::uint8_t> foldover_mask(const Ribbon& ribbon, const GridSpec& canvas,
                                         int tile_size) {
  // Saturating piece count per pixel, on the tiles the pieces touch.
  SparseRaster<std::uint8_t> coverage(canvas.width, canvas.height, 0, tile_size);
  SparseRaster<std::uint8_t> mask(canvas.width, canvas.height, 0, tile_size);
  for (const Piece& piece : ribbon.pieces) {
    double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
    for (const Vec2& w : {piece.top_left, piece.bottom_left, piece.bottom_right, piece.top_right}) {
      const Vec2 p = canvas.world_to_pixel(w);
      min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
      min_y = std::min(min_y, p.y), max_y = std::max(max_y, p.y);
    }
    const int c0 = std::max(0, int(std::floor(min_x)));
    const int c1 = std::min(canvas.width - 1, int(std::ceil(max_x)));
    const int r0 = std::max(0, int(std::floor(min_y)));
    const int r1 = std::min(canvas.height - 1, int(std::ceil(max_y)));
    for (int row = r0; row <= r1; ++row) {
      for (int col = c0; col <= c1; ++col) {
        const int w = piece_winding(piece, canvas.pixel_centre_world(col, row));
        if (w == 0) continue;
        const std::uint8_t count = coverage.at(col, row);
        if (w < 0 || std::abs(w) > 1 || count > 0) mask.set(col, row, 1);
        coverage.set(col, row, std::uint8_t(std::min(255, count + 1)));
      }
    }
  }
  return mask;
}

SparseRaster<std::uint8_t> combined_avoidance(const Ribbon& ribbon, const GridSpec& canvas,
                                              const SparseRaster<std::uint8_t>* forbidden) {
  if (forbidden && (forbidden->width() != canvas.width || forbidden->height() != canvas.height))
    fail("avoidance map is {}x{} pixels but the canvas is {}x{}", forbidden->width(),
         forbidden->height(), canvas.width, canvas.height);
  if (forbidden && forbidden->background() != 0)
    fail("avoidance map: absent tiles must read as free (background 0)");
  const int tile_size =
      forbidden ? forbidden->tile_size() : SparseRaster<std::uint8_t>::kDefaultTileSize;
  const SparseRaster<std::uint8_t> folds = foldover_mask(ribbon, canvas, tile_size);
  SparseRaster<std::uint8_t> mask(canvas.width, canvas.height, 0, tile_size);
  if (forbidden) {
    for (const TileIndex t : forbidden->tiles()) {
      const Raster<std::uint8_t>& from = *forbidden->tile(t);
      Raster<std::uint8_t>& to = mask.add_tile(t);
      for (std::size_t i = 0; i < from.pixels.size(); ++i) to.pixels[i] = from.pixels[i] ? 1 : 0;
    }
  }
  for (const TileIndex t : folds.tiles()) {
    const Raster<std::uint8_t>& from = *folds.tile(t);
    Raster<std::uint8_t>& to = mask.add_tile(t);
    for (std::size_t i = 0; i < from.pixels.size(); ++i) to.pixels[i] |= from.pixels[i];
  }
  return mask;
}

}  // namespace tw::detail
