#pragma once
// The avoidance canvas of one area polygon (docs/shape-patterns.md, "Memory"): a sparse lattice
// over the polygon's box whose tiles are allocated only where the polygon (grown by a margin)
// meets them, so its cells follow the polygon's area, not its box; estimated, and refused with
// the numbers, before anything is allocated.
#include <cstdint>
#include <string>

#include "raster/avoidance.hpp"
#include "raster/polygon.hpp"
#include "raster/sparse_raster.hpp"
#include "sketch/area_synthesis.hpp"

namespace tw {

// Cells per side of a canvas tile: small, so a thin diagonal polygon allocates a band about
// its own width.
inline constexpr int kAreaCanvasTile = 64;

struct AreaCanvas {
  GridSpec grid;  // cells of `cell` metres, edges on multiples of it in world coordinates
  SparseRaster<std::uint8_t> forbidden;
  std::int64_t allocated_cells = 0;  // at its peak (before empty tiles are freed)
};

// Fails (tw::Error) naming `label` (class and FID), the polygon's area, the scale, the cell and
// the estimated bytes (shapes and canvas cells) when they exceed memory_budget_bytes().
// `cell` <= 0: no canvas (the estimate of the shapes only).
void require_area_memory(const SupportHierarchy& hierarchy, const Polygon& polygon,
                         const AreaSynthesisParams& params, double cell, double margin,
                         const std::string& label);

// The canvas's tiles allocated (zeros) where the polygon grown by `margin` metres meets them.
AreaCanvas area_canvas(const Polygon& polygon, double cell, double margin);

// The canvas once everything forbidden is burnt: tiles with nothing forbidden freed.
SparseAvoidance finish_canvas(AreaCanvas&& canvas);

// Cells under the placed strokes (pixel-centre rule, exact buffers) that are forbidden: an
// independent check of the synthesis's test, burnt only on the canvas's forbidden tiles.
std::int64_t forbidden_touched(const AreaPattern& pattern, const SparseAvoidance& avoidance);

}  // namespace tw
