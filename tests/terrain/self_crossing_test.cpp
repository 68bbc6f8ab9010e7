// A feature that crosses itself meets itself as two features would (docs/junctions.md): a road
// on one level platform, a river at one water level.
#include <gtest/gtest.h>

#include <cmath>

#include "terrain/detail/profiles.hpp"
#include "terrain/height_ops.hpp"
#include "terrain_test_support.hpp"

namespace tw {
namespace {

constexpr int kSize = 200;

// East, north, west, then south through its own first leg at (100.5, 100.5): the first pass
// 80.5 m along, the second 298.5 m along.
const std::vector<Vec2> kLoop{
    {20.0, 100.5}, {150.0, 100.5}, {150.0, 160.0}, {100.5, 160.0}, {100.5, 20.0}};
constexpr double kFirstPass = 80.5;
constexpr double kSecondPass = 298.5;

TEST(SelfCrossing, ALoopRampMeetsItselfOnOneLevel) {
  const GridSpec grid = test::unit_grid(kSize);
  // Waves along both axes: the two passes of the road would grade to levels metres apart.
  const Raster<float> h = test::heights_from(grid, [](double x, double y) {
    return 50.0 + 10.0 * std::sin(x / 9.0) + 8.0 * std::sin(y / 7.0);
  });
  auto ramp = test::feature(FeatureKind::road, 1, kLoop, 6.0);
  ramp.road = {0.05, 1.0, 10.0, 30.0, std::nullopt, std::nullopt};
  Warnings warnings;
  const TerrainPlan plan = plan_terrain(h, grid, {ramp}, {}, warnings);
  ASSERT_EQ(plan.profiles.size(), 1u);
  const double first = detail::profile_at(plan.profiles[0], plan.steps[0], kFirstPass);
  const double second = detail::profile_at(plan.profiles[0], plan.steps[0], kSecondPass);
  EXPECT_NEAR(first, second, 1e-3);
  // Within grade along the whole road, the platform included.
  for (std::size_t k = 1; k < plan.profiles[0].size(); ++k) {
    EXPECT_LE(std::abs(plan.profiles[0][k] - plan.profiles[0][k - 1]), 0.05 * plan.steps[0] + 1e-4)
        << k;
  }
  EXPECT_TRUE(warnings.empty());
}

TEST(SelfCrossing, ARiverLoopMeetsItselfAtOneWaterLevel) {
  const GridSpec grid = test::unit_grid(kSize);
  // Falling east and north: the water surface drops to 84.5 m at the loop's far corner
  // (150, 160) and stays there, while at the first pass it is still 89.95 m.
  const Raster<float> h =
      test::heights_from(grid, [](double x, double y) { return 100.0 - 0.05 * x - 0.05 * y; });
  auto river = test::feature(FeatureKind::river, 2, kLoop, 4.0);
  river.river.depth = 1.0;
  // The flat water across the loop lies up to 7.5 m below the terrain: unbounded here, so that
  // the test sees the level alone (max_carve is tested in conform_test.cpp).
  river.river.max_carve = 100.0;
  const TerrainPlan plan = plan_terrain(h, grid, {river}, {});
  const auto& bed = plan.profiles[0];
  const double step = plan.steps[0];
  const double first = detail::profile_at(bed, step, kFirstPass);
  const double second = detail::profile_at(bed, step, kSecondPass);
  EXPECT_NEAR(second, 84.5 - 1.0, 0.05);
  EXPECT_NEAR(first, second, 1e-3);
  // Never rising downstream.
  for (std::size_t k = 1; k < bed.size(); ++k) EXPECT_LE(bed[k], bed[k - 1] + 1e-4) << k;
  // Upstream of the ramp before the first pass the river keeps its own level.
  EXPECT_NEAR(detail::profile_at(bed, step, 40.0), 100.0 - 0.05 * 60.0 - 0.05 * 100.5 - 1.0, 0.05);
}

}  // namespace
}  // namespace tw
