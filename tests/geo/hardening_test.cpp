// Inputs the geo module must refuse with one clear message (issue #9 items 2-5): heights,
// resolutions and widths that overflow later stages, a missing DEM, a CRS GDAL does not know.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "core/error.hpp"
#include "geo/features.hpp"
#include "geo/heightfield.hpp"
#include "geo_test_data.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

using test::DemSpec;
using test::error_of;
using test::TempDir;
using ::testing::HasSubstr;

TEST(GeoHardening, AHeightBeyondTheLimitIsRefusedNamingTheCell) {
  TempDir dir;
  const std::string path = (dir / "dem.tif").string();
  DemSpec spec;
  spec.value = [](int col, int row) { return col == 2 && row == 3 ? -3e38 : 100.0; };
  test::write_geotiff(path, spec);
  EXPECT_THAT(error_of([&] { read_heightfield(path); }),
              HasSubstr("dem.tif: cell (2, 3) holds a height of -3e+38 m, beyond +-100000 m"));
}

TEST(GeoHardening, AResolutionCoarserThanTheExtentIsRefused) {
  TempDir dir;
  const std::string path = (dir / "dem.tif").string();
  test::write_geotiff(path, DemSpec{});  // 10 x 10 cells of 10 m
  EXPECT_EQ(error_of([&] { read_heightfield(path, {.resolution = 1e12, .crs = {}}); }),
            path +
                ": resolution 1000000000000 m is coarser than the heightfield's extent (100 x "
                "100 m); the grid would be under one cell");
  // The whole extent as one cell is still a grid.
  EXPECT_EQ(read_heightfield(path, {.resolution = 100.0, .crs = {}}).grid.width, 1);
  DemSpec geographic;
  geographic.crs = "EPSG:4326";
  geographic.geotransform = {3.0, 0.0001, 0.0, 45.0, 0.0, -0.0001};
  const std::string lon_lat = (dir / "lon_lat.tif").string();
  test::write_geotiff(lon_lat, geographic);
  EXPECT_THAT(error_of([&] { read_heightfield(lon_lat, {.resolution = 1e9, .crs = {}}); }),
              HasSubstr("lon_lat.tif: 1e+09 x 1e+09 m pixels are coarser than its extent"));
}

TEST(GeoHardening, AResolutionGivingAnOversizedGridIsRefusedBeforeAllocating) {
  TempDir dir;
  const std::string path = (dir / "one_cell.tif").string();
  DemSpec spec;
  spec.width = spec.height = 1;
  spec.geotransform = {500000.0, 10000.0, 0.0, 5000000.0, 0.0, -10000.0};
  test::write_geotiff(path, spec);
  EXPECT_EQ(error_of([&] { read_heightfield(path, {.resolution = 0.1, .crs = {}}); }),
            path +
                ": resolution 0.1 m gives a 100000 x 100000 grid (37.3 GiB per float band); at "
                "most 1073741824 cells are allowed");
  GeneratedTerrain params;
  params.width = params.height = 65536;
  EXPECT_THAT(error_of([&] { generate_heightfield(params); }),
              HasSubstr("gives a 65536 x 65536 grid (16 GiB per float band)"));
}

TEST(GeoHardening, GeneratedTerrainNamesTheRealProblem) {
  GeneratedTerrain params;
  params.width = params.height = 8;
  params.pixel_size = 1e-9;
  EXPECT_EQ(error_of([&] { generate_heightfield(params); }),
            "generated:seed=1: pixel_size 1e-09 m is too small for origin (500000, 5000000): the "
            "origin lies over 1e15 pixels from 0");
  params.pixel_size = 10.0;
  params.relief = 1e308;
  EXPECT_EQ(error_of([&] { generate_heightfield(params); }),
            "generated:seed=1: relief must be in [0, 100000] metres, got 1e+308");
}

TEST(GeoHardening, AMissingDemOrAFolderSaysSo) {
  TempDir dir;
  EXPECT_EQ(error_of([&] { read_heightfield((dir / "absent.tif").string()); }),
            (dir / "absent.tif").string() + ": cannot open as a raster: no such file");
  EXPECT_EQ(error_of([&] { read_heightfield(dir.path().string()); }),
            dir.path().string() + ": cannot open as a raster: is a folder, not a file");
}

TEST(GeoHardening, AWidthOverTheLimitIsRefusedNamingTheFid) {
  TempDir dir;
  const std::string path = (dir / "wide.gpkg").string();
  test::write_vector(path, "GPKG", "lines", "EPSG:32631",
                     {{1, "LINESTRING (500100 4999500, 500900 4999500)", 1e12}});
  LineClassSpec spec;
  spec.name = "roads";
  spec.source.path = path;
  spec.width_attribute = "width";
  spec.default_width = 5.0;
  EXPECT_EQ(error_of([&] { read_line_features(spec, test::small_utm_grid()); }),
            path +
                ":lines: FID 1: width 1e+12 m is over the limit of 100000 m (from attribute "
                "'width')");
}

// GeoJSON reads a CRS that PROJ does not know as WGS 84: projected coordinates then are no
// longitude/latitude, which the message says (it used to say "out-of-range coordinate").
TEST(GeoHardening, AnUnknownCrsIsNamedAsTheCause) {
  TempDir dir;
  const std::string path = (dir / "unknown_crs.geojson").string();
  std::ofstream(path) << R"({"type": "FeatureCollection",
  "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::99999"}},
  "features": [{"type": "Feature", "properties": {},
    "geometry": {"type": "LineString", "coordinates": [[500100, 4999500], [500900, 4999500]]}}]})";
  LineClassSpec spec;
  spec.name = "roads";
  spec.source.path = path;
  spec.default_width = 5.0;
  const std::string message = error_of([&] { read_line_features(spec, test::small_utm_grid()); });
  EXPECT_THAT(message, HasSubstr("vertex 0 (500100, 4999500) is no longitude/latitude, yet the "
                                 "layer's CRS (WGS 84) is geographic: is the CRS right?"));
  EXPECT_THAT(message, HasSubstr("GeoJSON reads a CRS that PROJ does not know as WGS 84"));
}

}  // namespace
}  // namespace tw
