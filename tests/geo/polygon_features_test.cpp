#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "geo/features.hpp"
#include "geo_test_data.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

using test::error_of;
using test::TempDir;
using ::testing::AllOf;
using ::testing::HasSubstr;

double ring_area(const std::vector<Vec2>& ring) {
  double twice = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    twice += cross(ring[i], ring[(i + 1) % ring.size()]);
  }
  return std::abs(twice) / 2.0;
}

class PolygonFeatures : public ::testing::Test {
 protected:
  Heightfield grid = test::small_utm_grid();
  TempDir dir;
  Warnings warnings;
  VectorSource write(const std::vector<test::TestFeature>& features,
                     const std::string& name = "areas.gpkg") {
    const std::string path = (dir / name).string();
    test::write_vector(path, "GPKG", "areas", "EPSG:32631", features);
    return {path, "", ""};
  }
};

TEST_F(PolygonFeatures, RingsAndHolesInsideTheGrid) {
  const VectorSource source = write(
      {{5,
        "POLYGON ((500100 4999100,500500 4999100,500500 4999500,500100 4999500,500100 4999100),"
        "(500200 4999200,500300 4999200,500300 4999300,500200 4999300,500200 4999200))"}});
  const std::vector<PolygonFeature> polygons =
      read_polygon_features(source, grid, "existing.0", warnings);
  ASSERT_EQ(polygons.size(), 1u);
  EXPECT_EQ(polygons[0].fid, 5);
  ASSERT_EQ(polygons[0].rings.size(), 2u);
  EXPECT_EQ(polygons[0].rings[0].size(), 4u);  // the closing vertex is not repeated
  EXPECT_NEAR(ring_area(polygons[0].rings[0]), 400.0 * 400.0, 1e-6);
  EXPECT_NEAR(ring_area(polygons[0].rings[1]), 100.0 * 100.0, 1e-6);
  EXPECT_EQ(polygons[0].source, source.path + ":areas");
}

TEST_F(PolygonFeatures, ClippedToTheGridAndOutsideSkipped) {
  const VectorSource source = write(
      {{1,
        "POLYGON ((500800 4999800,501200 4999800,501200 5000200,500800 5000200,500800 4999800))"},
       {2, "POLYGON ((502000 4999800,502100 4999800,502100 4999900,502000 4999800))"},
       {3,
        "MULTIPOLYGON (((500100 4999100,500200 4999100,500200 4999200,500100 4999100)),"
        "((500300 4999100,500400 4999100,500400 4999200,500300 4999100)))"}});
  const std::vector<PolygonFeature> polygons =
      read_polygon_features(source, grid, "existing.0", warnings);
  ASSERT_EQ(polygons.size(), 3u);
  EXPECT_EQ(polygons[0].fid, 1);
  EXPECT_NEAR(ring_area(polygons[0].rings[0]), 200.0 * 200.0, 1e-6);
  for (const Vec2& p : polygons[0].rings[0]) {
    EXPECT_LE(p.x, 501000.0);
    EXPECT_LE(p.y, 5000000.0);
  }
  EXPECT_EQ(polygons[1].fid, 3);
  EXPECT_EQ(polygons[2].fid, 3);
  EXPECT_NEAR(ring_area(polygons[1].rings[0]), 5000.0, 1e-6);
}

TEST_F(PolygonFeatures, LinesWhereAreasAreExpectedNameFileAndFid) {
  VectorSource source = write({{8, "LINESTRING (500100 4999500,500200 4999500)"}}, "line.gpkg");
  EXPECT_THAT(error_of([&] { read_polygon_features(source, grid, "existing.0", warnings); }),
              AllOf(HasSubstr("line.gpkg"), HasSubstr("FID 8"), HasSubstr("Line String")));
}

// A bow tie (its ring crosses itself at 500150 4999150) is made valid by GEOS: two triangles
// of 50 x 100 / 2 m² each, with a warning naming the key and the FID.
TEST_F(PolygonFeatures, InvalidPolygonsAreMadeValidWithAWarning) {
  const VectorSource source = write(
      {{9,
        "POLYGON ((500100 4999100,500200 4999200,500200 4999100,500100 4999200,500100 4999100))"},
       {10, "POLYGON ((500300 4999300,500400 4999300,500400 4999400,500300 4999300))"}},
      "bowtie.gpkg");
  const std::vector<PolygonFeature> polygons =
      read_polygon_features(source, grid, "existing.0", warnings);
  double area = 0.0;
  int of_nine = 0;
  for (const PolygonFeature& p : polygons) {
    if (p.fid != 9) continue;
    ++of_nine;
    area += ring_area(p.rings[0]);
  }
  EXPECT_EQ(of_nine, 2);
  EXPECT_NEAR(area, 2 * 2500.0, 1e-6);
  ASSERT_EQ(warnings.size(), 1u);
  const Warning w = warnings.list()[0];
  EXPECT_EQ(w.code, "repaired");
  EXPECT_EQ(w.subject, "existing.0");
  EXPECT_EQ(w.fid, 9);
  EXPECT_THAT(w.message, AllOf(HasSubstr("bowtie.gpkg"), HasSubstr("made valid")));
}

// An invalid polygon off the grid is skipped without being judged.
TEST_F(PolygonFeatures, InvalidPolygonsOffTheGridAreNotJudged) {
  const VectorSource source = write(
      {{4,
        "POLYGON ((510100 4999100,510200 4999200,510200 4999100,510100 4999200,510100 4999100))"}});
  EXPECT_TRUE(read_polygon_features(source, grid, "existing.0", warnings).empty());
  EXPECT_TRUE(warnings.empty());
}

}  // namespace
}  // namespace tw
