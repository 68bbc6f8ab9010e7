#pragma once
// Small rasters and vector layers written with GDAL into a test's TempDir.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "geo/heightfield.hpp"

namespace tw::test {

struct DemSpec {
  int width = 10;
  int height = 10;
  std::array<double, 6> geotransform{500000.0, 10.0, 0.0, 5000000.0, 0.0, -10.0};
  std::string crs = "EPSG:32631";  // empty = no CRS at all
  std::optional<double> nodata;
  std::function<double(int col, int row)> value = [](int, int) { return 100.0; };
  int bands = 1;     // band b holds value + 1000 * (b - 1)
  std::string unit;  // GDAL unit type of every band; empty = none
};

// A Float32 GeoTIFF.
void write_geotiff(const std::string& path, const DemSpec& spec);

struct TestFeature {
  TestFeature(std::int64_t fid_, std::string wkt_, std::optional<double> width_ = std::nullopt,
              std::string kind_ = "road", std::vector<double> raw_points_ = {})
      : fid(fid_),
        wkt(std::move(wkt_)),
        width(width_),
        kind(std::move(kind_)),
        raw_points(std::move(raw_points_)) {}

  std::int64_t fid = 0;            // 0 = let the driver choose
  std::string wkt;                 // empty = no geometry
  std::optional<double> width;     // attribute "width"; unset = NULL
  std::string kind = "road";       // attribute "kind"
  std::vector<double> raw_points;  // when set, a LineString built from x,y pairs (may be NaN)
};

// A vector file with one layer (fields kind: string, width: real). driver: "GPKG", "GeoJSON",
// "ESRI Shapefile". crs empty = layer without CRS.
void write_vector(const std::string& path, const std::string& driver, const std::string& layer,
                  const std::string& crs, const std::vector<TestFeature>& features);

// A 100 x 100 grid of 10 m pixels in UTM 31N: x 500000..501000, y 4999000..5000000.
Heightfield small_utm_grid();

// (lon, lat) -> (x, y) with GeographicLib's UTM, zone 31 north: independent of OGR/PROJ.
std::array<double, 2> utm31_from_lon_lat(double lon, double lat);

// The message of the tw::Error that action throws, or "no tw::Error".
std::string error_of(const std::function<void()>& action);

}  // namespace tw::test
