#pragma once
// Warping a DEM into a north-up metric grid (gdalwarp as a library call).
#include <string>

#include "geo/detail/gdal_support.hpp"

namespace tw::detail {

struct WarpTarget {
  std::string crs_wkt;        // metric CRS of the output
  double pixel_width = 0.0;   // metres
  double pixel_height = 0.0;  // metres
};

// Band 1 of `source` warped (gdalwarp's `resampling`: "bilinear" or "cubic") into a virtual
// Float32 dataset with NaN as nodata (a warped VRT: each block is warped when read, on its own,
// so a window reads the same bits as the whole and holds only the blocks it meets).
// GDAL's warper never mixes a nodata cell into a height (it weighs valid neighbours only) and
// leaves an output cell nodata when the source cell under its centre is nodata, so holes
// neither fill nor shrink (tests/geo/heightfield_test.cpp checks both). `label` names the
// source in errors.
// `source` must outlive the result.
struct WarpedGrid {
  GdalDatasetPtr band_one;  // band 1 alone of a multi-band source, which `warped` reads
  GdalDatasetPtr warped;    // declared last: closed first
};
WarpedGrid warp_to_metric_grid(GDALDataset& source, const WarpTarget& target,
                               const std::string& label, const char* resampling);

}  // namespace tw::detail
