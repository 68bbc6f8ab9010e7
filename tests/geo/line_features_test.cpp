#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <GeographicLib/UTMUPS.hpp>

#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.hpp"
#include "geo/features.hpp"
#include "geo/geodesic.hpp"
#include "geo_test_data.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

using test::error_of;
using test::TempDir;
using test::TestFeature;
using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

// The test grid spans x 500000..501000, y 4999000..5000000 (UTM 31N).
class LineFeatures : public ::testing::Test {
 protected:
  Heightfield grid = test::small_utm_grid();
  TempDir dir;
  Warnings warnings;

  std::string write(const std::vector<TestFeature>& features, const std::string& crs = "EPSG:32631",
                    const std::string& name = "lines.gpkg", const std::string& driver = "GPKG") {
    const std::string path = (dir / name).string();
    test::write_vector(path, driver, "lines", crs, features);
    return path;
  }
  LineClassSpec spec_for(const std::string& path) {
    LineClassSpec spec;
    spec.name = "road";
    spec.source.path = path;
    spec.width_attribute = "width";
    spec.default_width = 4.0;
    return spec;
  }
};

TEST_F(LineFeatures, WhereFilterWidthAttributeAndDefaultWidth) {
  const std::string path =
      write({{1, "LINESTRING (500100 4999100,500200 4999200,500300 4999150)", 6.0, "road"},
             {2, "LINESTRING (500100 4999800,500400 4999800)", std::nullopt, "road"},
             {3, "LINESTRING (500500 4999500,500600 4999600)", 9.0, "river"}});
  LineClassSpec spec = spec_for(path);
  spec.source.where = "kind = 'road'";
  const std::vector<LineFeature> lines = read_line_features(spec, grid, warnings);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].fid, 1);
  EXPECT_EQ(lines[0].width, 6.0);
  EXPECT_FALSE(lines[0].closed);
  EXPECT_THAT(lines[0].points,
              ElementsAre(Vec2{500100, 4999100}, Vec2{500200, 4999200}, Vec2{500300, 4999150}));
  EXPECT_EQ(lines[0].source, path + ":lines");
  EXPECT_EQ(lines[1].fid, 2);
  EXPECT_EQ(lines[1].width, 4.0);  // NULL attribute: the class default
  EXPECT_THAT(lines[1].points, ElementsAre(Vec2{500100, 4999800}, Vec2{500400, 4999800}));

  spec.source.where.clear();
  spec.width_attribute.clear();
  const std::vector<LineFeature> all = read_line_features(spec, grid, warnings);
  ASSERT_EQ(all.size(), 3u);
  for (const LineFeature& line : all) EXPECT_EQ(line.width, 4.0);
}

TEST_F(LineFeatures, MultiLineStringPartsShareTheFid) {
  const std::string path = write(
      {{7, "MULTILINESTRING ((500100 4999100,500200 4999100),(500300 4999300,500300 4999400))",
        5.0}});
  const std::vector<LineFeature> lines = read_line_features(spec_for(path), grid, warnings);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].fid, 7);
  EXPECT_EQ(lines[1].fid, 7);
  EXPECT_THAT(lines[0].points, ElementsAre(Vec2{500100, 4999100}, Vec2{500200, 4999100}));
  EXPECT_THAT(lines[1].points, ElementsAre(Vec2{500300, 4999300}, Vec2{500300, 4999400}));
}

TEST_F(LineFeatures, ClosedRingStaysClosed) {
  const std::string path = write(
      {{4,
        "LINESTRING (500100 4999100,500300 4999100,500300 4999300,500100 4999300,500100 4999100)",
        3.0}});
  const std::vector<LineFeature> lines = read_line_features(spec_for(path), grid, warnings);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_TRUE(lines[0].closed);
  EXPECT_THAT(lines[0].points, ElementsAre(Vec2{500100, 4999100}, Vec2{500300, 4999100},
                                           Vec2{500300, 4999300}, Vec2{500100, 4999300}));
}

// Lon/lat of UTM 31N points from GeographicLib (independent of PROJ), written as EPSG:4326.
std::string lon_lat_wkt(const std::vector<Vec2>& utm_points, std::vector<Vec2>& lon_lat) {
  std::string wkt = "LINESTRING (";
  for (const Vec2& p : utm_points) {
    double lat = 0.0;
    double lon = 0.0;
    GeographicLib::UTMUPS::Reverse(31, true, p.x, p.y, lat, lon);
    lon_lat.push_back({lon, lat});
    wkt += fmt::format("{}{:.12f} {:.12f}", wkt.back() == '(' ? "" : ",", lon, lat);
  }
  return wkt + ")";
}

TEST_F(LineFeatures, ReprojectsFromWgs84InLonLatOrder) {
  const std::vector<Vec2> utm{{500150, 4999150}, {500450, 4999420}, {500800, 4999870}};
  std::vector<Vec2> lon_lat;
  const std::string wkt = lon_lat_wkt(utm, lon_lat);
  // GeoJSON is lon/lat by definition; a GeoPackage in EPSG:4326 declares lat/lon axis order.
  for (const auto& [name, driver] :
       {std::pair{"wgs84.geojson", "GeoJSON"}, std::pair{"wgs84.gpkg", "GPKG"}}) {
    const std::string path = write({{1, wkt, 5.0}}, "EPSG:4326", name, driver);
    const std::vector<LineFeature> lines = read_line_features(spec_for(path), grid, warnings);
    ASSERT_EQ(lines.size(), 1u) << driver;
    ASSERT_EQ(lines[0].points.size(), utm.size()) << driver;
    for (std::size_t i = 0; i < utm.size(); ++i) {
      EXPECT_NEAR(lines[0].points[i].x, utm[i].x, 1e-3) << driver << " " << i;
      EXPECT_NEAR(lines[0].points[i].y, utm[i].y, 1e-3) << driver << " " << i;
    }
  }
  // The metric length agrees with the geodesic one up to UTM's scale near its central meridian.
  const double metric = planar_length(utm);
  EXPECT_NEAR(metric / geodesic_length(lon_lat), 0.9996, 1e-5);
}

TEST_F(LineFeatures, GeographicFeaturesOnAWarpedGeographicDem) {
  // The DEM is in degrees, so it is warped into its centre's UTM zone; features in lon/lat
  // follow it there and keep their geodesic lengths.
  const std::string dem = (dir / "dem_4326.tif").string();
  test::DemSpec spec;
  spec.width = 200;
  spec.height = 150;
  spec.geotransform = {6.40, 0.001, 0.0, 45.40, 0.0, -0.001};
  spec.crs = "EPSG:4326";
  test::write_geotiff(dem, spec);
  const Heightfield field = read_heightfield(dem);

  const std::vector<Vec2> lon_lat{{6.42, 45.28}, {6.47, 45.31}, {6.53, 45.30}, {6.58, 45.33}};
  std::string wkt = "LINESTRING (";
  for (const Vec2& p : lon_lat) {
    wkt += fmt::format("{}{} {}", wkt.back() == '(' ? "" : ",", p.x, p.y);
  }
  const std::string path = write({{1, wkt + ")", 5.0}}, "EPSG:4326", "tm.geojson", "GeoJSON");
  const std::vector<LineFeature> lines = read_line_features(spec_for(path), field, warnings);
  ASSERT_EQ(lines.size(), 1u);
  ASSERT_EQ(lines[0].points.size(), 4u);
  const double geodesic = geodesic_length(lon_lat);
  EXPECT_GT(geodesic, 12000.0);
  EXPECT_LT(std::abs(planar_length(lines[0].points) / geodesic - 1.0), 1e-4);
  // The frame is the UTM zone of the DEM's centre (6.5 E: zone 32, issue #12): the vertex is
  // where GeographicLib's UTM puts it.
  int zone = 0;
  bool north = false;
  double x = 0.0, y = 0.0;
  GeographicLib::UTMUPS::Forward(45.31, 6.47, zone, north, x, y, 32);
  EXPECT_NEAR(lines[0].points[1].x, x, 1.0);
  EXPECT_NEAR(lines[0].points[1].y, y, 1.0);
}

TEST_F(LineFeatures, CurvedGeometriesAreLinearized) {
  const std::string path =
      write({{3, "CIRCULARSTRING (500300 4999500,500500 4999700,500700 4999500)", 5.0}});
  const std::vector<LineFeature> lines = read_line_features(spec_for(path), grid, warnings);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_GT(lines[0].points.size(), 10u);
  // Half a circle of radius 200 m.
  EXPECT_NEAR(planar_length(lines[0].points), std::numbers::pi * 200.0, 1.0);
  for (const Vec2& p : lines[0].points) {
    EXPECT_NEAR(distance(p, Vec2{500500, 4999500}), 200.0, 1e-6);
  }
}

// GeoPackage's other curve types: a CompoundCurve (straight + arc) and a MultiCurve.
TEST_F(LineFeatures, CompoundCurvesAndMultiCurvesAreLinearized) {
  const std::string path = write({{4,
                                   "COMPOUNDCURVE ((500100 4999500,500300 4999500),"
                                   "CIRCULARSTRING (500300 4999500,500500 4999700,500700 4999500))",
                                   5.0},
                                  {5,
                                   "MULTICURVE ((500100 4999100,500200 4999100),"
                                   "CIRCULARSTRING (500300 4999200,500400 4999300,500500 4999200))",
                                   5.0}});
  const std::vector<LineFeature> lines = read_line_features(spec_for(path), grid, warnings);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].fid, 4);
  EXPECT_NEAR(planar_length(lines[0].points), 200.0 + std::numbers::pi * 200.0, 1.0);
  EXPECT_EQ(lines[1].fid, 5);
  EXPECT_THAT(lines[1].points, ElementsAre(Vec2{500100, 4999100}, Vec2{500200, 4999100}));
  EXPECT_EQ(lines[2].fid, 5);
  EXPECT_NEAR(planar_length(lines[2].points), std::numbers::pi * 100.0, 1.0);
  EXPECT_TRUE(warnings.empty());
}

// Clipped to the grid grown by half the width (2.5 m) plus clip_margin (7.5 m): 10 m halo.
TEST_F(LineFeatures, ClipsToTheGridExtentPlusTheHalo) {
  const std::string path = write({
      {1, "LINESTRING (500500 4999500,501500 4999500)", 5.0},
      {2, "LINESTRING (500800 4999200,501200 4999200,501200 4999300,500800 4999300)", 5.0},
      {3, "LINESTRING (500900 4999400,501100 4999400,501100 4999600,500900 4999600,500900 4999400)",
       5.0},
  });
  LineClassSpec spec = spec_for(path);
  spec.clip_margin = 7.5;
  const std::vector<LineFeature> lines = read_line_features(spec, grid, warnings);
  ASSERT_EQ(lines.size(), 4u);
  // Leaves the grid: cut 10 m beyond its east edge.
  EXPECT_EQ(lines[0].fid, 1);
  EXPECT_THAT(lines[0].points, ElementsAre(Vec2{500500, 4999500}, Vec2{501010, 4999500}));
  // Leaves and comes back: two pieces, same FID, in the line's direction.
  EXPECT_EQ(lines[1].fid, 2);
  EXPECT_EQ(lines[2].fid, 2);
  EXPECT_THAT(lines[1].points, ElementsAre(Vec2{500800, 4999200}, Vec2{501010, 4999200}));
  EXPECT_THAT(lines[2].points, ElementsAre(Vec2{501010, 4999300}, Vec2{500800, 4999300}));
  // A ring crossing the edge becomes one open piece (not split at the ring's start vertex).
  EXPECT_EQ(lines[3].fid, 3);
  EXPECT_FALSE(lines[3].closed);
  ASSERT_EQ(lines[3].points.size(), 4u);
  EXPECT_EQ(lines[3].points.front().x, 501010.0);
  EXPECT_EQ(lines[3].points.back().x, 501010.0);
  EXPECT_NEAR(planar_length(lines[3].points), 420.0, 1e-6);
  EXPECT_TRUE(warnings.empty());
}

TEST_F(LineFeatures, FeaturesFullyOutsideAreSkipped) {
  const std::string path = write({{1, "LINESTRING (502000 4999500,503000 4999500)", 5.0},
                                  {2, "LINESTRING (500100 4999500,500200 4999500)", 5.0},
                                  {3, "LINESTRING (499000 4999500,499990 4999500)", 5.0}});
  const std::vector<LineFeature> lines = read_line_features(spec_for(path), grid, warnings);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].fid, 2);
}

TEST_F(LineFeatures, MissingFileUnknownLayerAndBadWhereNameTheCulprit) {
  LineClassSpec spec = spec_for((dir / "absent.gpkg").string());
  EXPECT_THAT(error_of([&] { read_line_features(spec, grid, warnings); }),
              HasSubstr("absent.gpkg"));

  const std::string path = write({{1, "LINESTRING (500100 4999500,500200 4999500)", 5.0}});
  spec = spec_for(path);
  spec.source.layer = "rivers";
  EXPECT_THAT(error_of([&] { read_line_features(spec, grid, warnings); }),
              AllOf(HasSubstr("lines.gpkg"), HasSubstr("rivers"), HasSubstr("lines")));
  spec = spec_for(path);
  spec.source.where = "kind = = 'road'";
  EXPECT_THAT(error_of([&] { read_line_features(spec, grid, warnings); }),
              AllOf(HasSubstr("lines.gpkg"), HasSubstr("kind = = 'road'")));
  spec = spec_for(path);
  spec.width_attribute = "lanes";
  EXPECT_THAT(error_of([&] { read_line_features(spec, grid, warnings); }),
              AllOf(HasSubstr("lines.gpkg"), HasSubstr("lanes")));
}

TEST_F(LineFeatures, LayerWithoutCrsIsAnError) {
  const std::string path = write({{1, "LINESTRING (500100 4999500,500200 4999500)", 5.0}}, "",
                                 "no_crs.shp", "ESRI Shapefile");
  EXPECT_THAT(error_of([&] { read_line_features(spec_for(path), grid, warnings); }),
              AllOf(HasSubstr("no_crs.shp"), HasSubstr("CRS")));
}

TEST_F(LineFeatures, BadGeometriesNameFileAndFid) {
  struct Case {
    TestFeature feature;
    std::string says;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Case> cases = {
      {{11, "POINT (500100 4999500)", 5.0}, "Point"},
      {{12, "POLYGON ((500100 4999100,500200 4999100,500200 4999200,500100 4999100))", 5.0},
       "Polygon"},
      {{15, "", 5.0, "road", {500100, 4999500, nan, 4999600}}, "non-finite"},
      {{16, "LINESTRING (500100 4999500,1e12 4999500)", 5.0}, "out-of-range"},
      {{17, "LINESTRING (500100 4999500,500200 4999500)", -1.0}, "width"},
      {{18, "", 5.0}, "no geometry"},
  };
  for (const Case& c : cases) {
    const std::string path =
        write({c.feature}, "EPSG:32631", fmt::format("bad_{}.gpkg", c.feature.fid));
    EXPECT_THAT(error_of([&] { read_line_features(spec_for(path), grid, warnings); }),
                AllOf(HasSubstr(fmt::format("bad_{}.gpkg", c.feature.fid)),
                      HasSubstr(fmt::format("FID {}", c.feature.fid)), HasSubstr(c.says)));
  }
}

TEST_F(LineFeatures, NonPositiveDefaultWidthIsAnError) {
  const std::string path = write({{21, "LINESTRING (500100 4999500,500200 4999500)", 5.0}});
  LineClassSpec spec = spec_for(path);
  spec.width_attribute.clear();
  spec.default_width = 0.0;
  EXPECT_THAT(error_of([&] { read_line_features(spec, grid, warnings); }),
              AllOf(HasSubstr("lines.gpkg"), HasSubstr("FID 21"), HasSubstr("width")));
}

TEST_F(LineFeatures, ImpossibleLatitudeInAGeographicLayerIsAnError) {
  const std::string path =
      write({{31, "LINESTRING (3 45,3 95)", 5.0}}, "EPSG:4326", "bad_lat.geojson", "GeoJSON");
  EXPECT_THAT(error_of([&] { read_line_features(spec_for(path), grid, warnings); }),
              AllOf(HasSubstr("bad_lat.geojson"), HasSubstr("FID 31")));
}

}  // namespace
}  // namespace tw
