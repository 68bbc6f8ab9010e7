// Plans and conformance read heights through windows (geo/height_sampler.hpp): the same plan,
// bit for bit, as over the whole raster, reading only the cells along the features.
#include <gtest/gtest.h>

#include <cstring>

#include "geo/height_sampler.hpp"
#include "geo/heightfield_source.hpp"
#include "terrain/conform.hpp"
#include "terrain/height_ops.hpp"
#include "terrain_test_support.hpp"

namespace tw {
namespace {

GeneratedTerrain world(int size) {
  GeneratedTerrain params;
  params.width = params.height = size;
  params.pixel_size = 10.0;
  params.seed = 11;
  params.relief = 120.0;
  return params;
}

// Roads meeting at a T and crossing, and a river, in world metres of `world(...)`.
std::vector<TerrainFeature> features_near_the_corner() {
  const double x = 500000, y = 5000000;
  auto through = test::feature(FeatureKind::road, 1, {{x + 100, y - 300}, {x + 2500, y - 420}}, 6);
  auto branch = test::feature(FeatureKind::road, 2, {{x + 1300, y - 360}, {x + 1250, y - 2000}}, 5);
  auto cross = test::feature(FeatureKind::road, 3, {{x + 200, y - 1500}, {x + 2400, y - 900}}, 6);
  auto river = test::feature(FeatureKind::river, 4,
                             {{x + 50, y - 2600}, {x + 900, y - 2300}, {x + 2700, y - 2500}}, 8);
  return {through, branch, cross, river};
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(WindowedPlan, EqualsThePlanOverTheWholeRaster) {
  const GeneratedTerrain params = world(600);
  const Heightfield whole = generate_heightfield(params);
  const auto features = features_near_the_corner();
  const TerrainPlan expected = plan_terrain(whole.height, whole.grid, features, {});

  const auto source = open_generated_heightfield(params);
  HeightSampler heights(*source, {32, 4 * 32 * 32 * 4});  // four blocks: evictions on the way
  Warnings warnings;
  const TerrainPlan plan = plan_terrain(heights, features, {}, warnings);
  ASSERT_EQ(plan.profiles.size(), expected.profiles.size());
  for (std::size_t i = 0; i < plan.profiles.size(); ++i) {
    EXPECT_TRUE(same_bits(plan.profiles[i], expected.profiles[i])) << "feature " << i;
    EXPECT_EQ(plan.steps[i], expected.steps[i]);
    EXPECT_EQ(plan.earthwork[i].max_cut, expected.earthwork[i].max_cut);
    EXPECT_EQ(plan.earthwork[i].max_fill, expected.earthwork[i].max_fill);
  }
  EXPECT_LE(heights.peak_bytes(), 4 * 32 * 32 * 4);
}

// A 4096 x 4096 world (64 MiB of heights) with features in one corner: the plan reads the
// blocks along them, not the world.
TEST(WindowedPlan, ReadsOnlyTheBlocksAlongTheFeatures) {
  const auto source = open_generated_heightfield(world(4096));
  HeightSampler heights(*source, {64, std::int64_t(1) << 20});
  Warnings warnings;
  const TerrainPlan plan = plan_terrain(heights, features_near_the_corner(), {}, warnings);
  ASSERT_EQ(plan.profiles.size(), 4u);
  EXPECT_GT(plan.earthwork[0].max_cut + plan.earthwork[0].max_fill, 0.0);
  // The features span ~280 x 270 cells of the corner: well under 2 % of the world's 16.8 M.
  EXPECT_LT(source->cells_read(), 300000);
  EXPECT_GT(source->cells_read(), 0);
}

TEST(WindowedConform, EqualsConformanceOverTheWholeRaster) {
  const GeneratedTerrain params = world(400);
  const Heightfield whole = generate_heightfield(params);
  const Curve line{{{500100, 4998500}, {501200, 4998000}, {503500, 4998900}}, false};
  const ConformOptions options{150.0};
  const ConformResult expected = conform_line(whole.height, whole.grid, line, options);
  ASSERT_TRUE(expected.conformed);
  const auto source = open_generated_heightfield(params);
  // One block cached (re-reads on the way) and a cache that holds the corridor: same line.
  for (const std::int64_t cap : {16 * 16 * 4, 256 * 16 * 16 * 4}) {
    HeightSampler heights(*source, {16, cap});
    const std::int64_t before = source->cells_read();
    const ConformResult got = conform_line(heights, line, options);
    ASSERT_EQ(got.line.points.size(), expected.line.points.size());
    for (std::size_t i = 0; i < got.line.points.size(); ++i) {
      EXPECT_EQ(got.line.points[i].x, expected.line.points[i].x);
      EXPECT_EQ(got.line.points[i].y, expected.line.points[i].y);
    }
    EXPECT_EQ(got.max_move, expected.max_move);
    if (cap > 16 * 16 * 4) {
      // The blocks of the corridor's bounding box (23 x 9 blocks of 16 x 16 cells), once.
      EXPECT_LE(source->cells_read() - before, 23 * 9 * 16 * 16);
    }
  }
}

}  // namespace
}  // namespace tw
