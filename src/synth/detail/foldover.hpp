#pragma once
// Fold-overs of a ribbon (Section 3.1): canvas pixels whose centre is covered by more than one
// piece (overdraw at hairpins and close passes) or by the inverted lobe of a self-crossing
// piece. A private helper: the raster module's avoidance maps may include these already;
// OR-ing twice is harmless.
#include <cstdint>

#include "core/grid.hpp"
#include "ribbon/ribbon.hpp"

namespace tw::detail {

// 1 where the ribbon folds over itself, over the whole `canvas`.
Raster<std::uint8_t> foldover_mask(const Ribbon& ribbon, const GridSpec& canvas);

// forbidden (may be null) OR the fold-overs of `ribbon`.
Raster<std::uint8_t> combined_avoidance(const Ribbon& ribbon, const GridSpec& canvas,
                                        const Raster<std::uint8_t>* forbidden);

}  // namespace tw::detail
