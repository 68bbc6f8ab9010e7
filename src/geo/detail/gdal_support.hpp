#pragma once
// Small RAII and error helpers over the GDAL/OGR C and C++ APIs, shared by the readers.
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <memory>
#include <string>

namespace tw::detail {

// GDALAllRegister once per process (thread-safe).
void ensure_gdal_registered();

struct GdalDatasetCloser {
  void operator()(GDALDataset* dataset) const { GDALClose(GDALDataset::ToHandle(dataset)); }
};
using GdalDatasetPtr = std::unique_ptr<GDALDataset, GdalDatasetCloser>;

// While alive, GDAL errors are recorded (for our messages) instead of printed.
class QuietGdalErrors {
 public:
  QuietGdalErrors();
  ~QuietGdalErrors();
  QuietGdalErrors(const QuietGdalErrors&) = delete;
  QuietGdalErrors& operator=(const QuietGdalErrors&) = delete;
};

// The last GDAL error message, or "unknown GDAL error" when GDAL gave none.
std::string last_gdal_error();

// Why GDALDataset::Open(path) just failed: GDAL's message when it gave one, else "no such
// file", "is a folder, not a file" or "not a format GDAL can read" (GDAL is silent for these).
std::string open_failure(const std::string& path);

// Sets srs from WKT, "EPSG:n", a PROJ string... with x = easting/longitude and y =
// northing/latitude whatever the authority's axis order says (OAMS_TRADITIONAL_GIS_ORDER).
// False when the text is empty or not a CRS.
bool import_traditional_srs(OGRSpatialReference& srs, const std::string& user_input);

// WKT2 of a spatial reference (what Heightfield::crs_wkt holds).
std::string to_wkt(const OGRSpatialReference& srs);

}  // namespace tw::detail
