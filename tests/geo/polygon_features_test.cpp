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
  const std::vector<PolygonFeature> polygons = read_polygon_features(source, grid);
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
  const std::vector<PolygonFeature> polygons = read_polygon_features(source, grid);
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

TEST_F(PolygonFeatures, LinesAndInvalidPolygonsNameFileAndFid) {
  VectorSource source = write({{8, "LINESTRING (500100 4999500,500200 4999500)"}}, "line.gpkg");
  EXPECT_THAT(error_of([&] { read_polygon_features(source, grid); }),
              AllOf(HasSubstr("line.gpkg"), HasSubstr("FID 8"), HasSubstr("Line String")));
  source = write(
      {{9,
        "POLYGON ((500100 4999100,500200 4999200,500200 4999100,500100 4999200,500100 4999100))"}},
      "bowtie.gpkg");
  EXPECT_THAT(error_of([&] { read_polygon_features(source, grid); }),
              AllOf(HasSubstr("bowtie.gpkg"), HasSubstr("FID 9"), HasSubstr("valid")));
}

}  // namespace
}  // namespace tw
