#pragma once
// A GDAL VRT mosaic of tile files (GDALBuildVRT from the GDAL library), so QGIS and GDAL open a
// tiled world as one raster.
#include <filesystem>
#include <vector>

namespace tw {

// Writes `vrt` over `sources` (GeoTIFFs of one layer: same bands, CRS and pixel size). Paths
// under the VRT's folder are stored relative to it, so the folder can move. Where sources
// overlap the later one is read; tiled runs write identical overlapping pixels. Throws
// tw::Error naming the VRT when GDAL fails.
void write_vrt_mosaic(const std::filesystem::path& vrt,
                      const std::vector<std::filesystem::path>& sources);

}  // namespace tw
