#pragma once
// Fold-overs of a ribbon (Section 3.1): canvas pixels whose centre is covered by more than one
// piece (overdraw at hairpins and close passes) or by the inverted lobe of a self-crossing
// piece. A private helper: the raster module's avoidance maps may include these already;
// OR-ing twice is harmless. Sparse: only tiles where the ribbon folds are allocated.
#include <cstdint>

#include "core/grid.hpp"
#include "raster/sparse_raster.hpp"
#include "ribbon/ribbon.hpp"

namespace tw::detail {

// 1 where the ribbon folds over itself, over `canvas` (tiles of `tile_size` cells).
SparseRaster<std::uint8_t> foldover_mask(
    const Ribbon& ribbon, const GridSpec& canvas,
    int tile_size = SparseRaster<std::uint8_t>::kDefaultTileSize);

// forbidden (may be null; canvas-sized) OR the fold-overs of `ribbon`, 1 or 0, on forbidden's
// tiles (their size) plus those where the ribbon folds.
SparseRaster<std::uint8_t> combined_avoidance(const Ribbon& ribbon, const GridSpec& canvas,
                                              const SparseRaster<std::uint8_t>* forbidden);

}  // namespace tw::detail
