// The ingest's line repairs through the cache (detail/repair_cache.hpp, issue #23 item 2): a
// rerun repairs no piece, one with a moved line repairs that line's piece alone, and the lines
// and warnings are those of an ingest without a cache, in the same order.
#include "pipeline/detail/repair_cache.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>

#include "pipeline/config.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/stage_options.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

// Five roads on the test DEM (x 500000..500640, y 5000000..5000640): FID 2 has a spike and a
// duplicate vertex (a `repaired` warning), FID 4 crosses itself.
std::vector<test::VectorFeature> five_roads(double fid3_shift = 0.0) {
  return {{"LINESTRING (500050 5000100,500600 5000100)", 6.0},
          {"LINESTRING (500050 5000200,500300 5000200,500300 5000200.001,500300 5000300,"
           "500300.5 5000200.5,500600 5000200)",
           6.0},
          {fmt::format("LINESTRING (500050 {0},500300 {0},500600 {0})", 5000300 + fid3_shift), 6.0},
          {"LINESTRING (500100 5000400,500500 5000400,500500 5000500,500300 5000500,"
           "500300 5000350)",
           6.0},
          {"LINESTRING (500100 5000600,500600 5000550)", 6.0}};
}

class RepairCacheIngest : public ::testing::Test {
 protected:
  struct Loaded {
    std::vector<LineFeature> lines;
    std::vector<Warning> warnings;
    int repaired = -1;  // pieces repaired through the cache; -1 without one
  };

  // The roads of `gpkg` (in the test's folder), through a fresh RepairCache (a new run's) over
  // the test's cache folder, or without a cache.
  Loaded load(const std::string& gpkg, bool with_cache) {
    const PipelineConfig config =
        parse_pipeline("version: 1\nheightfield: dem.tif\nfeatures:\n  roads: { source: " + gpkg +
                           ", kind: road, width: 6 }\n",
                       "p.yaml", dir_.path());
    Warnings warnings;
    const Heightfield heightfield =
        detail::load_heightfield(detail::heightfield_input(config), warnings);
    Loaded loaded;
    if (with_cache) {
      detail::RepairCache cache(dir_ / "cache", warnings);
      loaded.lines =
          detail::load_feature_class(config.features[0], heightfield, warnings, cache.memo());
      loaded.repaired = cache.pieces_repaired();
    } else {
      loaded.lines = detail::load_feature_class(config.features[0], heightfield, warnings);
    }
    loaded.warnings = warnings.list();
    return loaded;
  }

  static void expect_same(const Loaded& cached, const Loaded& clean) {
    ASSERT_EQ(cached.lines.size(), clean.lines.size());
    for (std::size_t i = 0; i < clean.lines.size(); ++i) {
      EXPECT_EQ(cached.lines[i].fid, clean.lines[i].fid);
      EXPECT_EQ(cached.lines[i].points, clean.lines[i].points) << "FID " << clean.lines[i].fid;
      EXPECT_EQ(cached.lines[i].closed, clean.lines[i].closed);
    }
    ASSERT_EQ(cached.warnings.size(), clean.warnings.size());
    for (std::size_t i = 0; i < clean.warnings.size(); ++i) {
      EXPECT_EQ(cached.warnings[i].code, clean.warnings[i].code);
      EXPECT_EQ(cached.warnings[i].subject, clean.warnings[i].subject);
      EXPECT_EQ(cached.warnings[i].fid, clean.warnings[i].fid);
      EXPECT_EQ(cached.warnings[i].message, clean.warnings[i].message);
    }
  }

  void SetUp() override {
    test::write_dem(dir_ / "dem.tif");
    test::write_layer(dir_ / "map.gpkg", "roads", five_roads());
    test::write_layer(dir_ / "moved.gpkg", "roads", five_roads(12.0));
  }

  test::TempDir dir_;
};

TEST_F(RepairCacheIngest, ARerunRepairsOnlyTheMovedLine) {
  const Loaded clean = load("map.gpkg", false);
  ASSERT_EQ(clean.lines.size(), 5u);
  ASSERT_EQ(clean.warnings.size(), 1u);
  EXPECT_EQ(clean.warnings[0].code, "repaired");
  EXPECT_EQ(clean.warnings[0].fid, 2);

  const Loaded first = load("map.gpkg", true);
  EXPECT_EQ(first.repaired, 5);  // every piece, stored
  expect_same(first, clean);
  const Loaded again = load("map.gpkg", true);
  EXPECT_EQ(again.repaired, 0);  // every piece from the cache, the warning with it
  expect_same(again, clean);

  const Loaded moved = load("moved.gpkg", true);
  EXPECT_EQ(moved.repaired, 1);  // FID 3 alone
  expect_same(moved, load("moved.gpkg", false));
  EXPECT_EQ(load("map.gpkg", true).repaired, 0);  // moved back: its first repair
}

// A corrupt entry is the warning cache_corrupt (plan.repair), repaired again and replaced.
TEST_F(RepairCacheIngest, ACorruptEntryIsAWarningAndRepairedAgain) {
  load("map.gpkg", true);
  const fs::directory_entry entry = *fs::directory_iterator(dir_ / "cache" / "plan" / "repair");
  fs::permissions(entry.path(), fs::perms::owner_write, fs::perm_options::add);
  std::ofstream(entry.path(), std::ios::binary | std::ios::trunc) << "TWCACHE1 and less";
  Loaded corrupt = load("map.gpkg", true);
  EXPECT_EQ(corrupt.repaired, 1);
  ASSERT_FALSE(corrupt.warnings.empty());
  EXPECT_EQ(corrupt.warnings[0].code, "cache_corrupt");
  EXPECT_EQ(corrupt.warnings[0].subject, "plan.repair");
  corrupt.warnings.erase(corrupt.warnings.begin());
  expect_same(corrupt, load("map.gpkg", false));
  EXPECT_EQ(load("map.gpkg", true).repaired, 0);  // whole again
}

}  // namespace
}  // namespace tw
