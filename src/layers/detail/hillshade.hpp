#pragma once
// The preview's hillshade, by GDAL's own (GDALDEMProcessing "hillshade").
#include "core/grid.hpp"

namespace tw::detail {

// The light on each cell of `heights` (metres; cells of cell_x by cell_y metres, north up) under
// a sun from the north-west (315 degrees) 45 degrees up, slopes exaggerated 2x, in [0, 1]:
// GDAL's hillshade with Zevenbergen-Thorne's central differences and -compute_edges, so a
// neighbour off the grid or without a finite height is extrapolated from the other side (a
// one-sided difference). Non-finite cells are NaN; a finite cell whose slope overflows
// (extreme heights) is fully lit. GDAL quantizes to 254 steps: each value is within 0.5/254
// of the exact cosine.
Raster<float> hillshade(const Raster<float>& heights, double cell_x, double cell_y);

}  // namespace tw::detail
