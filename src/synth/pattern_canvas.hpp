#pragma once
// The canvas of one feature's pattern (docs/patterns.md, docs/performance.md): cells of the
// synthesis resolution on a lattice fixed in world coordinates, windowed to the ribbon and
// sparse, with tiles only where the ribbon and a halo of kCanvasHalo cells pass. Everything the
// synthesis reads (valid positions, stitching, rendering for the violation check) lies within
// that halo of a piece, so a sparse canvas gives the same bits as a dense one.
#include <cstdint>
#include <string>

#include "core/grid.hpp"
#include "raster/sparse_raster.hpp"
#include "ribbon/curve.hpp"
#include "ribbon/ribbon.hpp"
#include "synth/exemplar.hpp"
#include "synth/synthesize.hpp"

namespace tw {

// Cells kept around each piece's box: synthesis loops over the box plus one cell (only cells
// with a subsample inside the piece count), and one more of slack.
inline constexpr int kCanvasHalo = 2;

// The largest canvas bounding box: the canvas is sparse, so its box may exceed kMaxGridCells
// (a 100 km diagonal river at 1 m holds 4e9 cells), but the tile directory (4 bytes a tile)
// grows with it: 2^42 cells is a 2000 km square at 1 m, a 256 MiB directory of 256² tiles.
inline constexpr double kMaxCanvasCells = 4398046511104.0;  // 2^42

// Cells of `resolution` metres whose edges lie on multiples of `resolution` in world
// coordinates, covering the ribbon's pieces plus `halo_m`: the same cells whatever the output
// grid, so placements never depend on it. A box over kMaxCanvasCells, or with a side beyond an
// int, is a tw::Error starting with `label` (the feature).
GridSpec synthesis_canvas(const Ribbon& ribbon, double resolution, double halo_m,
                          const std::string& label);

// The canvas tiles a synthesis of `ribbon` reads: ribbon_tiles with kCanvasHalo.
std::vector<TileIndex> canvas_tiles(const Ribbon& ribbon, const GridSpec& canvas, int tile_size);

// A closed curve starting at its first piece whose corners and centre all lie on free canvas
// cells: the synthesizer's closed mode needs piece 0 to have a valid position, and a ring often
// starts where it meets another road (a junction disc). Unchanged when no piece is clear.
Curve start_in_the_clear(const Curve& curve, const Ribbon& ribbon, const GridSpec& canvas,
                         const SparseRaster<std::uint8_t>& forbidden);

struct PatternCheck {
  std::int64_t violations = 0;        // opaque pattern pixels on forbidden ones (0 when correct)
  SparseRaster<std::uint8_t> opaque;  // 1 where the rendered pattern has coverage > 0
};

// Renders the pattern on every tile of `forbidden` (memory bounded by a tile, whatever the
// feature's length) and counts opaque pixels on forbidden ones with the synthesizer's criterion
// (count_avoidance_violations); marks every covered pixel in `opaque` (same tiles).
PatternCheck check_pattern(const Exemplar& exemplar, const Ribbon& ribbon,
                           const Synthesis& synthesis, const GridSpec& canvas,
                           const SparseRaster<std::uint8_t>& forbidden, bool stitch);

}  // namespace tw
