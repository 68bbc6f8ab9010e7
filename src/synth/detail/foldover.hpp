#pragma once
// The synthesizer's avoidance: the caller's map OR the ribbon's own fold-overs (Section 3.1),
// the latter from the raster module's one fold-over mask (raster/foldover.hpp).
#include <cstdint>

#include "core/grid.hpp"
#include "raster/sparse_raster.hpp"
#include "ribbon/ribbon.hpp"

namespace tw::detail {

// forbidden (may be null; canvas-sized) OR the fold-overs of `ribbon`, 1 or 0, on forbidden's
// tiles (their size) plus those within two cells of a piece.
SparseRaster<std::uint8_t> combined_avoidance(const Ribbon& ribbon, const GridSpec& canvas,
                                              const SparseRaster<std::uint8_t>* forbidden);

}  // namespace tw::detail
