// Real river centrelines as they come (WDB II of GSHHG through `gmt coast`, tests/data/README.md):
// the messy ones are repaired with a warning each, and one whose mess lies off the DEM reads
// without a word.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogr_geometry.h>

#include <map>
#include <set>

#include "geo/features.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

using ::testing::HasSubstr;

bool is_simple(const LineFeature& line) {
  OGRLineString curve;
  for (const Vec2& p : line.points) curve.addPoint(p.x, p.y);
  if (line.closed) curve.addPoint(line.points.front().x, line.points.front().y);
  return curve.IsSimple();
}

// The 7 segments of -R2/8/46/50 that are not simple: zigzags where the line doubles back on
// itself (a spike, 160-180 degrees), some crossing the segment before. Over a UTM 31N grid of
// 1 km cells that holds them all (x 400..850 km, y 5180..5500 km).
TEST(RealRivers, EveryMessyWdb2LineIsRepairedWithAWarningNamingItsFid) {
  GeneratedTerrain params;
  params.width = 450;
  params.height = 320;
  params.pixel_size = 1000.0;
  params.origin_x = 400000.0;
  params.origin_y = 5500000.0;
  const Heightfield grid = generate_heightfield(params);
  LineClassSpec spec;
  spec.name = "rivers";
  spec.subject = "features.rivers";
  spec.source.path = (test::source_dir() / "tests/data/wdb2_rivers_messy.geojson").string();
  spec.default_width = 30.0;
  Warnings warnings;
  const std::vector<LineFeature> lines = read_line_features(spec, grid, warnings);

  const std::set<std::int64_t> messy{4, 27, 33, 77, 104, 110, 123};
  std::set<std::int64_t> read;
  for (const LineFeature& line : lines) {
    read.insert(line.fid);
    EXPECT_TRUE(is_simple(line)) << "FID " << line.fid;
  }
  EXPECT_EQ(read, messy);
  std::map<std::int64_t, std::string> repaired;
  for (const Warning& w : warnings.list()) {
    EXPECT_EQ(w.code, "repaired");
    EXPECT_EQ(w.subject, "features.rivers");
    ASSERT_TRUE(w.fid.has_value());
    repaired[*w.fid] = w.message;
  }
  EXPECT_EQ(repaired.size(), messy.size());
  for (const std::int64_t fid : messy) EXPECT_THAT(repaired[fid], HasSubstr("spike")) << fid;
}

// Segment 1 doubles back at 49.17 N, 30 km south of the Luxembourg DEM (49.44..49.70 N); its
// last 2 km lie on the DEM. Judged before clipping, it failed the run ("intersects itself").
TEST(RealRivers, AMessOffTheDemDoesNotFailOrWarn) {
  const std::string samples = (test::source_dir() / "samples").string();
  const Heightfield dem = read_heightfield(samples + "/dem_wgs84.tif");
  LineClassSpec spec;
  spec.name = "rivers";
  spec.source.path = (test::source_dir() / "tests/data/wdb2_rivers_luxembourg.geojson").string();
  spec.default_width = 30.0;
  Warnings warnings;
  const std::vector<LineFeature> lines = read_line_features(spec, dem, warnings);
  int pieces_of_one = 0;
  for (const LineFeature& line : lines) {
    pieces_of_one += line.fid == 1;
    EXPECT_TRUE(is_simple(line)) << "FID " << line.fid;
  }
  EXPECT_EQ(pieces_of_one, 1);
  for (const Warning& w : warnings.list()) EXPECT_NE(w.fid, 1) << to_string(w);
}

}  // namespace
}  // namespace tw
