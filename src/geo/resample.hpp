#pragma once
// Reading a heightfield between its cells, nodata-aware: NaN cells are never mixed into a
// height. Used to resample a DEM onto another north-up grid of the same CRS (a finer output
// resolution, a close-up region) and by the terrain stage to sample profiles.
#include "core/grid.hpp"
#include "geo/heightfield.hpp"

namespace tw {

// Bilinear from the valid cells among the four around `world` (weights renormalized); NaN when
// none is valid or the point is off the grid.
double sample_height_bilinear(const Raster<float>& height, const GridSpec& grid, Vec2 world);

// Catmull-Rom (Keys' cubic convolution with a = -0.5, GDAL's "cubic") over the 4 x 4 cells
// around `world`, cells beyond the grid's edge replicated from it; the bilinear read when any
// of the 16 is nodata, or when `world` lies beyond the outer cell centres.
double sample_height_cubic(const Raster<float>& height, const GridSpec& grid, Vec2 world);

inline constexpr int kMaxSamplesPerSide = 32;

// `height` (over `from`) read at every cell of `to` (same CRS) with `resampling`: at its centre,
// or, for cells larger than the source's, the mean over ceil(ratio)^2 points spread over the
// cell (no aliasing when downsampling), at most kMaxSamplesPerSide^2 of them so the work per
// cell stays bounded whatever the ratio. NaN where the cell of `from` under the centre is
// nodata (holes neither fill nor shrink).
Raster<float> resample_heights(const Raster<float>& height, const GridSpec& from,
                               const GridSpec& to, Resampling resampling);

// The same for `window` of `to` alone, bit for bit the matching window of resample_heights:
// `source` holds `source_window` of `from`, at least resample_source_window(from, to, window).
Raster<float> resample_heights_window(const Raster<float>& source, const Window& source_window,
                                      const GridSpec& from, const GridSpec& to,
                                      const Window& window, Resampling resampling);
// The cells of `from` that resampling `window` of `to` reads (clipped to `from`).
Window resample_source_window(const GridSpec& from, const GridSpec& to, const Window& window);

}  // namespace tw
