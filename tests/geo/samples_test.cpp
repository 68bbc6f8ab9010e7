// The real sample data of samples/ (see samples/README.md) through the geo readers.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <map>

#include "geo/features.hpp"
#include "geo/geodesic.hpp"
#include "geo/heightfield.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

// The lon/lat vertices of every line of a GeoJSON file, by FID (read with OGR directly).
std::map<std::int64_t, std::vector<Vec2>> lon_lat_lines(const std::string& path) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> dataset(
      GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  std::map<std::int64_t, std::vector<Vec2>> lines;
  if (!dataset) return lines;
  for (const auto& feature : *dataset->GetLayer(0)) {
    const OGRLineString* line = feature->GetGeometryRef()->toLineString();
    for (const OGRPoint& p : *line) lines[feature->GetFID()].push_back({p.getX(), p.getY()});
  }
  return lines;
}

TEST(Samples, LuxembourgLinesKeepTheirGeodesicLengthInTheDemsMetricFrame) {
  const std::string samples = (test::source_dir() / "samples").string();
  const Heightfield dem = read_heightfield(samples + "/dem_wgs84.tif");
  // 30 arc-second cells at 49.57 N: about 603 m east-west and 927 m north-south.
  EXPECT_NEAR(dem.grid.pixel_width, 602.8, 1.0);
  EXPECT_NEAR(dem.grid.pixel_height, 926.8, 1.0);
  ASSERT_TRUE(dem.nodata_value.has_value());

  Warnings warnings;
  LineClassSpec spec;
  spec.source.path = samples + "/lines_wgs84.geojson";
  spec.width_attribute = "width";
  const std::vector<LineFeature> lines = read_line_features(spec, dem, warnings);
  const auto reference = lon_lat_lines(spec.source.path);
  ASSERT_FALSE(lines.empty());
  int compared = 0;
  for (const LineFeature& line : lines) {
    const std::vector<Vec2>& lon_lat = reference.at(line.fid);
    // The DEM covers 6.1167..6.525 E, 49.4417..49.70 N: lines leaving it are clipped. Lines
    // inside, even touching its edge, come back whole.
    bool inside = true;
    for (const Vec2& p : lon_lat) {
      inside = inside && p.x >= 6.1166 && p.x <= 6.5251 && p.y >= 49.4416 && p.y <= 49.7001;
    }
    if (!inside) continue;
    ASSERT_EQ(line.points.size(), lon_lat.size()) << "FID " << line.fid;
    const double geodesic = geodesic_length(lon_lat);
    EXPECT_LT(std::abs(planar_length(line.points) / geodesic - 1.0), 1e-3)
        << "FID " << line.fid << ": " << geodesic << " m";
    EXPECT_TRUE(line.width == 90.0 || line.width == 7.0) << line.width;
    ++compared;
  }
  EXPECT_EQ(compared, 3);  // FID 0 starts south of the DEM
}

TEST(Samples, OlindaDemResampledToSixMetres) {
  const std::string samples = (test::source_dir() / "samples").string();
  const Heightfield native = read_heightfield(samples + "/dem.tif");
  const Heightfield fine = read_heightfield(samples + "/dem.tif", {.resolution = 6.0, .crs = {}});
  EXPECT_EQ(fine.grid.pixel_width, 6.0);
  // Same extent, 15 times the pixels per axis.
  EXPECT_NEAR(fine.grid.width * 6.0, native.grid.width * native.grid.pixel_width, 6.0);
  EXPECT_NEAR(fine.grid.origin_x, native.grid.origin_x, 1e-6);
  // Bilinear upsampling stays within the source's range.
  float low = 1e9f, high = -1e9f;
  for (float h : native.height.pixels) low = std::min(low, h), high = std::max(high, h);
  for (float h : fine.height.pixels) {
    ASSERT_FALSE(std::isnan(h));
    ASSERT_GE(h, low - 1e-3f);
    ASSERT_LE(h, high + 1e-3f);
  }
  // Roads are read onto it whole (the ring road stays a closed curve).
  Warnings warnings;
  LineClassSpec roads;
  roads.source = {samples + "/map.gpkg", "roads", ""};
  roads.width_attribute = "width";
  const std::vector<LineFeature> lines = read_line_features(roads, fine, warnings);
  EXPECT_EQ(lines.size(), 5u);
  int closed = 0;
  for (const LineFeature& line : lines) closed += line.closed;
  EXPECT_EQ(closed, 1);
}

}  // namespace
}  // namespace tw
