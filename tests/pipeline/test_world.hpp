#pragma once
// Small GDAL data sets made inside a test's TempDir: a DEM and vector layers (from WKT).
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tw::test {

struct DemSpec {
  int width = 64;
  int height = 64;
  double origin_x = 500000.0;
  double origin_y = 5000640.0;
  double pixel_size = 10.0;
  std::string crs = "EPSG:32631";  // "" = no CRS
  std::optional<double> nodata{};
  bool all_nodata = false;  // every cell holds the nodata value
  // bumps: a smooth slope with bumps (100..200 m); plane_east: 100 m + 2 m per column (contours
  // run north-south); flat: 100 m everywhere.
  enum class Surface { bumps, plane_east, flat } surface = Surface::bumps;
};

// A GeoTIFF of `spec.surface`.
void write_dem(const std::filesystem::path& path, const DemSpec& spec = {});

struct VectorFeature {
  VectorFeature(std::string wkt, std::optional<double> width = std::nullopt)
      : wkt(std::move(wkt)), width(width) {}
  VectorFeature(std::string wkt, double width, std::map<std::string, std::string> text)
      : wkt(std::move(wkt)), width(width), text(std::move(text)) {}
  // A LineString from raw points, which may hold NaN (WKT cannot).
  VectorFeature(std::vector<std::array<double, 2>> points, double width)
      : width(width), points(std::move(points)) {}

  std::string wkt;              // "" = a LineString of `points`
  std::optional<double> width;  // the `width` attribute (null when absent)
  std::vector<std::array<double, 2>> points;
  // String attributes (e.g. bridge=yes, surface=sett): one column per key over the layer.
  std::map<std::string, std::string> text;
};

// Adds a layer to a GeoPackage (created when missing), or writes a Shapefile (.shp, whose
// one layer is named after the file); crs "" = a layer without CRS.
void write_layer(const std::filesystem::path& path, const std::string& layer,
                 const std::vector<VectorFeature>& features, const std::string& crs = "EPSG:32631");

// Copies the top-left `width` x `height` pixels of a raster into `dst` in GDAL driver `format`
// (GDALTranslate, the library call of gdal_translate): a small exemplar cut from a sample.
void crop_raster(const std::filesystem::path& src, const std::filesystem::path& dst,
                 const char* format, int width, int height);

}  // namespace tw::test
