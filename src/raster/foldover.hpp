#pragma once
// Fold-overs of a ribbon (Zhou et al. 2013, Section 3.1): where the ribbon overdraws itself the
// pattern would be drawn twice, so those pixels are forbidden.
#include <cstdint>

#include <vector>

#include "core/grid.hpp"
#include "raster/polygon.hpp"
#include "raster/sparse_raster.hpp"
#include "ribbon/ribbon.hpp"

namespace tw {

// Window-sized mask, 1 on fold-over pixels: every piece quad is rasterized (pixel-centre rule),
// and a pixel is a fold-over when it is covered by two pieces that are not adjacent (i and i+1,
// and N-1 and 0 on a closed ribbon, share an edge and never count), or lies in the inverted lobe
// of a "bow-tie" piece whose right edge crosses its left edge. Near passes of the same ribbon
// (a hairpin narrower than the ribbon) count. Seamless across windows like rasterize.hpp.
Raster<std::uint8_t> foldover_mask(const Ribbon& ribbon, const GridSpec& grid,
                                   const Window& window);

// Sets 1 on the fold-over pixels of every allocated tile of `mask` (over `grid`).
void add_foldovers(const Ribbon& ribbon, const GridSpec& grid, SparseRaster<std::uint8_t>& mask);

// The pieces' quadrilaterals as polygons (the ribbon's footprint; a bow-tie piece is filled
// even-odd).
std::vector<Polygon> piece_polygons(const Ribbon& ribbon);

}  // namespace tw
