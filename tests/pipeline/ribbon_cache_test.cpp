// The ribbons stage through the cache (detail/ribbon_cache.hpp, issue #23 item 2): a moved line
// makes its own ribbon alone and searches the junctions near it alone, and the stage's result
// equals the stage run without a cache, bit for bit, whether the line gains or loses a junction.
#include "pipeline/detail/ribbon_cache.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "pipeline/detail/plan_fields.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

// Six roads of 6 m: r0 and r1 cross, r2 ends 5 m short of r0, r3-r5 far away east.
std::vector<std::vector<LineFeature>> six_roads() {
  std::vector<LineFeature> roads;
  const std::vector<std::vector<Vec2>> shapes{{{0, 0}, {100, 0}},      {{50, -50}, {50, 50}},
                                              {{20, 5}, {20, 40}},     {{900, 0}, {1000, 0}},
                                              {{950, -50}, {950, 50}}, {{800, 300}, {1000, 300}}};
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    LineFeature& road = roads.emplace_back();
    road.fid = std::int64_t(i);
    road.points = shapes[i];
    road.width = 6.0;
  }
  return {roads};
}

const detail::RibbonOptions kRibbonCacheOptions{{{"roads", 5.0, false, 8.0}}, 0.5};
const GridSpec kRibbonCacheGrid{300, 100, -100.0, 200.0, 4.0, 4.0};

// What a cached ribbons stage made and searched, and the junctions it found.
struct CachedStageCounts {
  int made = 0;
  std::size_t searched = 0;
  std::size_t junctions = 0;
};

// The stage through a fresh RibbonCache over `cache` (a new run's), checked against the stage
// without a cache.
CachedStageCounts expect_cached_stage_is_clean(const fs::path& cache,
                                               const std::vector<std::vector<LineFeature>>& lines) {
  Warnings cached_warnings, clean_warnings;
  detail::RibbonCache ribbon_cache(cache, cached_warnings);
  const detail::FeatureRibbons cached = detail::make_feature_ribbons(
      kRibbonCacheOptions, lines, kRibbonCacheGrid, cached_warnings, ribbon_cache.steps());
  const detail::FeatureRibbons clean =
      detail::make_feature_ribbons(kRibbonCacheOptions, lines, kRibbonCacheGrid, clean_warnings);
  EXPECT_EQ(detail::to_bytes(cached.ribbons), detail::to_bytes(clean.ribbons));
  EXPECT_EQ(cached.lengths, clean.lengths);
  EXPECT_EQ(cached.junction_discs, clean.junction_discs);
  EXPECT_EQ(cached.synthesis_junction_discs, clean.synthesis_junction_discs);
  EXPECT_EQ(cached.synthesis_junctions, clean.synthesis_junctions);
  EXPECT_EQ(cached_warnings.size(), clean_warnings.size());
  return {ribbon_cache.ribbons_made(), ribbon_cache.curves_searched(), clean.junction_discs.size()};
}

TEST(RibbonCache, AMovedLineGainsAndLosesAJunctionAndTheStageIsACleanOnes) {
  test::TempDir dir;
  std::vector<std::vector<LineFeature>> lines = six_roads();
  CachedStageCounts counts = expect_cached_stage_is_clean(dir.path(), lines);
  EXPECT_EQ(counts.made, 6);
  EXPECT_EQ(counts.searched, 12u);  // every curve, at both tolerances
  EXPECT_EQ(counts.junctions, 2u);  // r0 x r1, r3 x r4

  counts = expect_cached_stage_is_clean(dir.path(), lines);
  EXPECT_EQ(counts.made, 0);
  EXPECT_EQ(counts.searched, 0u);  // the latest search's curves: its junctions as found

  for (Vec2& p : lines[0][2].points) p.y -= 5.0;  // r2 now ends on r0: a T-junction
  counts = expect_cached_stage_is_clean(dir.path(), lines);
  EXPECT_EQ(counts.made, 1);
  // r0 and r2 at both tolerances: not r1 (its crossing with r0 is 30 m away), not r3-r5.
  EXPECT_EQ(counts.searched, 4u);
  EXPECT_EQ(counts.junctions, 3u);

  for (Vec2& p : lines[0][2].points) p.y += 5.0;  // back where it was: its first ribbon, reused
  counts = expect_cached_stage_is_clean(dir.path(), lines);
  EXPECT_EQ(counts.made, 0);
  EXPECT_EQ(counts.searched, 4u);
  EXPECT_EQ(counts.junctions, 2u);
}

// A corrupt latest search is the warning cache_corrupt and a search of every curve.
TEST(RibbonCache, ACorruptJunctionSearchIsAWarningAndSearchedWhole) {
  test::TempDir dir;
  std::vector<std::vector<LineFeature>> lines = six_roads();
  expect_cached_stage_is_clean(dir.path(), lines);
  for (const auto& entry : fs::directory_iterator(dir / "plan" / "junctions")) {
    fs::permissions(entry.path(), fs::perms::owner_write, fs::perm_options::add);
    std::ofstream(entry.path(), std::ios::binary | std::ios::trunc) << "TWCACHE1 and less";
  }
  for (Vec2& p : lines[0][2].points) p.y -= 5.0;
  Warnings warnings;
  detail::RibbonCache ribbon_cache(dir.path(), warnings);
  detail::make_feature_ribbons(kRibbonCacheOptions, lines, kRibbonCacheGrid, warnings,
                               ribbon_cache.steps());
  EXPECT_EQ(ribbon_cache.curves_searched(), 12u);
  ASSERT_EQ(warnings.size(), 2u);
  for (const Warning& w : warnings.list()) {
    EXPECT_EQ(w.code, "cache_corrupt");
    EXPECT_EQ(w.subject, "plan.junctions");
  }
  EXPECT_EQ(expect_cached_stage_is_clean(dir.path(), lines).searched, 0u);  // whole again
}

}  // namespace
}  // namespace tw
