#include "synth/detail/foldover.hpp"

#include "core/error.hpp"
#include "raster/foldover.hpp"

namespace tw::detail {

SparseRaster<std::uint8_t> combined_avoidance(const Ribbon& ribbon, const GridSpec& canvas,
                                              const SparseRaster<std::uint8_t>* forbidden) {
  if (forbidden && (forbidden->width() != canvas.width || forbidden->height() != canvas.height))
    fail("avoidance map is {}x{} pixels but the canvas is {}x{}", forbidden->width(),
         forbidden->height(), canvas.width, canvas.height);
  if (forbidden && forbidden->background() != 0)
    fail("avoidance map: absent tiles must read as free (background 0)");
  const int tile_size =
      forbidden ? forbidden->tile_size() : SparseRaster<std::uint8_t>::kDefaultTileSize;
  SparseRaster<std::uint8_t> mask(canvas.width, canvas.height, 0, tile_size);
  if (forbidden) {
    for (const TileIndex t : forbidden->tiles()) {
      const Raster<std::uint8_t>& from = *forbidden->tile(t);
      Raster<std::uint8_t>& to = mask.add_tile(t);
      for (std::size_t i = 0; i < from.pixels.size(); ++i) to.pixels[i] = from.pixels[i] ? 1 : 0;
    }
  }
  // Every pixel a piece covers lies within a cell of its box: those tiles hold all fold-overs.
  add_tiles(mask, ribbon_tiles(ribbon, canvas, tile_size, 2));
  add_foldovers(ribbon, canvas, mask);
  return mask;
}

}  // namespace tw::detail
