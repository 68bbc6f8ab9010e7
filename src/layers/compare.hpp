#pragma once
// Two raster files compared band by band (terraweave diff): how many pixels differ, by how
// much at most and where. Bands are matched by name (GeoTIFF band descriptions, EXR channel
// names). Reads a few rows at a time, so memory follows the row, not the image.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace tw {

struct BandDifference {
  std::string band;
  std::int64_t differing = 0;        // pixels whose values differ (NaN equals NaN)
  std::int64_t nodata_mismatch = 0;  // of those, NaN in one file and a value in the other
  double max_abs = 0.0;              // the largest |a - b| over pixels holding values in both
  int col = -1, row = -1;            // where it is (-1: no such pixel)
  double a = 0.0, b = 0.0;           // the two values there
};

struct RasterDifference {
  std::string size_mismatch;  // "W x H vs W x H" when the sizes differ ("" = same size)
  std::vector<std::string> only_in_a, only_in_b;  // band names
  std::vector<BandDifference> bands;              // every band in both, in a's order
  bool identical() const;
};

// GeoTIFFs (and anything GDAL opens) through GDAL, .exr through OpenImageIO. Throws
// tw::Error naming the file when it cannot be read.
RasterDifference compare_rasters(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace tw
