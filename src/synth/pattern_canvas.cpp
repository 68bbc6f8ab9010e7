#include "synth/pattern_canvas.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "raster/footprint.hpp"
#include "synth/render.hpp"

namespace tw {

GridSpec synthesis_canvas(const Ribbon& ribbon, double resolution, double halo_m,
                          const std::string& label) {
  const auto [lo, hi] = ribbon_box(ribbon);
  const double x0 = std::floor((lo.x - halo_m) / resolution) * resolution;
  const double y1 = std::ceil((hi.y + halo_m) / resolution) * resolution;
  GridSpec grid;
  grid.pixel_width = grid.pixel_height = resolution;
  grid.origin_x = x0;
  grid.origin_y = y1;
  // Sized in double before any int conversion: an absurd width or resolution is an error.
  const double columns = std::ceil((hi.x + halo_m - x0) / resolution);
  const double rows = std::ceil((y1 - (lo.y - halo_m)) / resolution);
  constexpr double kMaxSide = 2147483647.0;
  if (!(columns >= 1.0 && rows >= 1.0 && columns <= kMaxSide && rows <= kMaxSide &&
        columns * rows <= kMaxCanvasCells)) {
    fail(
        "{}: a synthesis canvas of {} m cells would span {:.3g} x {:.3g} cells (at most {:.3g} "
        "cells); raise synthesis_resolution or check the feature's width",
        label, resolution, columns, rows, kMaxCanvasCells);
  }
  grid.width = int(columns);
  grid.height = int(rows);
  return grid;
}

std::vector<TileIndex> canvas_tiles(const Ribbon& ribbon, const GridSpec& canvas, int tile_size) {
  return ribbon_tiles(ribbon, canvas, tile_size, kCanvasHalo);
}

Curve start_in_the_clear(const Curve& curve, const Ribbon& ribbon, const GridSpec& canvas,
                         const SparseRaster<std::uint8_t>& forbidden) {
  auto free_at = [&](Vec2 world) {
    const Vec2 p = canvas.world_to_pixel(world);
    return !forbidden.at(int(std::floor(p.x)), int(std::floor(p.y)));
  };
  for (std::size_t k = 0; k < ribbon.pieces.size(); ++k) {
    const Piece& piece = ribbon.pieces[k];
    const Vec2 centre =
        0.25 * (piece.top_left + piece.bottom_left + piece.bottom_right + piece.top_right);
    if (!(free_at(piece.top_left) && free_at(piece.bottom_left) && free_at(piece.bottom_right) &&
          free_at(piece.top_right) && free_at(centre))) {
      continue;
    }
    if (k == 0) return curve;
    const std::vector<double> cumulative = cumulative_lengths(curve);
    const double start = double(k) * ribbon.delta;
    Curve rotated;
    rotated.closed = true;
    rotated.points.push_back(point_at(curve, cumulative, start));
    const std::size_t n = curve.points.size();
    std::size_t first = 0;
    while (first < n && cumulative[first] <= start) ++first;
    for (std::size_t i = 0; i < n; ++i) rotated.points.push_back(curve.points[(first + i) % n]);
    return without_duplicates(rotated);
  }
  return curve;
}

PatternCheck check_pattern(const Exemplar& exemplar, const Ribbon& ribbon,
                           const Synthesis& synthesis, const GridSpec& canvas,
                           const SparseRaster<std::uint8_t>& forbidden, bool stitch) {
  // Renders at most kBlock x kBlock cells at once (a dense canvas is one large tile).
  constexpr int kBlock = 512;
  PatternCheck check;
  check.opaque = SparseRaster<std::uint8_t>(canvas.width, canvas.height, 0, forbidden.tile_size());
  for (const TileIndex t : forbidden.tiles()) {
    const Window tile = forbidden.tile_window(t);
    for (int row0 = tile.row0; row0 < tile.row_end(); row0 += kBlock) {
      for (int col0 = tile.col0; col0 < tile.col_end(); col0 += kBlock) {
        const Window window{col0, row0, std::min(kBlock, tile.col_end() - col0),
                            std::min(kBlock, tile.row_end() - row0)};
        const RenderedPattern rendered =
            render_pattern(exemplar, ribbon, synthesis, canvas, window, stitch);
        for (int row = 0; row < window.height; ++row)
          for (int col = 0; col < window.width; ++col)
            if (rendered.coverage.at(col, row) > 0.0f)
              check.opaque.set(window.col0 + col, window.row0 + row, 1);
        check.violations += count_avoidance_violations(rendered, forbidden);
      }
    }
  }
  return check;
}

}  // namespace tw
