#include <gtest/gtest.h>

#include <cmath>

#include "terrain/height_ops.hpp"
#include "terrain/splat.hpp"
#include "terrain_test_support.hpp"

namespace tw {
namespace {

// A 200 m grid of 1 m cells; an east-west road along world y = 100.5 (the centres of row 99)
// in three OSM-style ways: approach 1 (x 5..60), structure 2 (x 60..140), approach 3
// (x 140..195). Approach caps reach 3 + 1 + 10 = 14 m past their ends (x < 74, x > 126).
constexpr int kSize = 200;
constexpr int kRoadRow = 99;

std::vector<TerrainFeature> road_with(Structure structure) {
  RoadProfile profile{0.08, 1.0, 10.0, 20.0, std::nullopt, std::nullopt};
  auto a = test::feature(FeatureKind::road, 1, {{5.0, 100.5}, {60.0, 100.5}}, 6.0);
  auto s = test::feature(FeatureKind::road, 2, {{60.0, 100.5}, {140.0, 100.5}}, 6.0);
  auto b = test::feature(FeatureKind::road, 3, {{140.0, 100.5}, {195.0, 100.5}}, 6.0);
  s.structure = structure;
  s.layer = structure == Structure::bridge ? 1 : -1;
  for (auto* f : {&a, &s, &b}) f->road = profile;
  return {a, s, b};
}

// A river flowing south along x = 100.5 (width 8, depth 2: reach 4 + 3 + 5 = 12 m).
TerrainFeature river() {
  auto r = test::feature(FeatureKind::river, 10, {{100.5, 195.0}, {100.5, 5.0}}, 8.0);
  r.river = {2.0, 3.0, 5.0, 0.0, std::nullopt};
  return r;
}

const TerrainFeature& by_fid(const TerrainPlan& plan, std::int64_t fid, std::size_t* index) {
  for (std::size_t i = 0; i < plan.features.size(); ++i)
    if (plan.features[i].fid == fid) {
      *index = i;
      return plan.features[i];
    }
  throw std::runtime_error("no such fid");
}

// The deck is the straight line between the approaches' graded heights at its two ends.
void expect_straight_deck(const TerrainPlan& plan) {
  std::size_t a = 0, s = 0, b = 0;
  by_fid(plan, 1, &a);
  by_fid(plan, 2, &s);
  by_fid(plan, 3, &b);
  const std::vector<float>& deck = plan.profiles[s];
  ASSERT_GE(deck.size(), 3u);
  EXPECT_FLOAT_EQ(deck.front(), plan.profiles[a].back());
  EXPECT_FLOAT_EQ(deck.back(), plan.profiles[b].front());
  for (std::size_t k = 0; k < deck.size(); ++k) {
    const double t = double(k) / double(deck.size() - 1);
    EXPECT_NEAR(deck[k], deck.front() + (deck.back() - deck.front()) * t, 1e-4) << k;
  }
}

TEST(Structures, ABridgeLeavesTheRiverCarvedAndTheGroundUnderItUntouched) {
  const GridSpec grid = test::unit_grid(kSize);
  // A V valley along the river, falling 1 m per 10 m southwards.
  auto valley = [](double x, double y) { return 40.0 + 0.3 * std::abs(x - 100.5) + 0.1 * y; };
  const Raster<float> before = test::heights_from(grid, valley);
  std::vector<TerrainFeature> features = road_with(Structure::bridge);
  features.push_back(river());
  const TerrainPlan plan = plan_terrain(before, grid, features, {});
  expect_straight_deck(plan);
  Raster<float> h = before;
  apply_terrain(h, grid, Window::whole(grid), plan);
  // Under the bridge, beyond the approaches' caps and the river's banks: untouched.
  for (int col = 75; col <= 87; ++col) {
    EXPECT_EQ(h.at(col, kRoadRow), before.at(col, kRoadRow)) << col;
    EXPECT_EQ(h.at(200 - col, kRoadRow), before.at(200 - col, kRoadRow)) << 200 - col;
  }
  // The river is carved under the bridge as anywhere else (its bed is depth below the surface).
  EXPECT_LE(h.at(100, kRoadRow), before.at(100, kRoadRow) - 1.9f);
  EXPECT_NEAR(h.at(100, kRoadRow), h.at(100, kRoadRow + 40) + 4.0f, 0.2f);  // 40 m upstream
  // The approaches are graded: they hold their profiles on their centrelines.
  EXPECT_NE(h.at(40, kRoadRow), before.at(40, kRoadRow));
  // The deck paints nothing: the river bed keeps its splat under the bridge.
  const SplatLayers splat = compute_splat(grid, Window::whole(grid), features, {});
  EXPECT_EQ(splat.weights[1].at(80, kRoadRow), 0.0f);    // road
  EXPECT_GT(splat.weights[1].at(30, kRoadRow), 0.99f);   // road, on an approach
  EXPECT_GT(splat.weights[3].at(100, kRoadRow), 0.99f);  // riverbed
}

TEST(Structures, ABridgeOverARoadIsNotPinnedToIt) {
  const GridSpec grid = test::unit_grid(kSize);
  // Terrain that rises north: the north-south road follows it, the bridge does not.
  auto slope = [](double x, double y) { return 20.0 + 0.06 * y + 2.0 * std::sin(x / 15.0); };
  const Raster<float> before = test::heights_from(grid, slope);
  auto under = test::feature(FeatureKind::road, 20, {{100.5, 10.0}, {100.5, 190.0}}, 6.0);
  under.road = {0.08, 1.0, 10.0, 20.0, std::nullopt, std::nullopt};
  std::vector<TerrainFeature> features = road_with(Structure::bridge);
  features.push_back(under);
  const TerrainPlan with_bridge = plan_terrain(before, grid, features, {});
  const TerrainPlan alone = plan_terrain(before, grid, {under}, {});
  std::size_t i = 0;
  by_fid(with_bridge, 20, &i);
  // Not a crossing: the road under the bridge keeps exactly its own grading.
  EXPECT_EQ(with_bridge.profiles[i], alone.profiles[0]);
  expect_straight_deck(with_bridge);
  // The same road at grade would be pinned to the crossing's mean level.
  features[1].structure = Structure::ground;
  features[1].layer = 1;  // ... unless it is on another layer
  const TerrainPlan other_layer = plan_terrain(before, grid, features, {});
  by_fid(other_layer, 20, &i);
  EXPECT_EQ(other_layer.profiles[i], alone.profiles[0]);
  features[1].layer = 0;
  const TerrainPlan at_grade = plan_terrain(before, grid, features, {});
  by_fid(at_grade, 20, &i);
  EXPECT_NE(at_grade.profiles[i], alone.profiles[0]);
}

TEST(Structures, ARoadEndingOnTheSideOfAnotherLayerIsNoTJunction) {
  const GridSpec grid = test::unit_grid(kSize);
  auto slope = [](double x, double y) { return 20.0 + 0.05 * x + 3.0 * std::sin(y / 12.0); };
  const Raster<float> before = test::heights_from(grid, slope);
  auto through = test::feature(FeatureKind::road, 1, {{10.0, 100.5}, {190.0, 100.5}}, 6.0);
  auto ending = test::feature(FeatureKind::road, 2, {{100.5, 10.0}, {100.5, 100.5}}, 6.0);
  for (auto* f : {&through, &ending}) f->road = {0.08, 1.0, 10.0, 20.0, std::nullopt, std::nullopt};
  const TerrainPlan alone = plan_terrain(before, grid, {ending}, {});
  const TerrainPlan t_junction = plan_terrain(before, grid, {through, ending}, {});
  std::size_t i = 0;
  by_fid(t_junction, 2, &i);
  EXPECT_NE(t_junction.profiles[i], alone.profiles[0]);  // at grade: pinned to the through road
  ending.layer = 1;
  const TerrainPlan layered = plan_terrain(before, grid, {through, ending}, {});
  by_fid(layered, 2, &i);
  EXPECT_EQ(layered.profiles[i], alone.profiles[0]);
}

TEST(Structures, ATunnelLeavesTheHillUntouchedBetweenItsPortals) {
  const GridSpec grid = test::unit_grid(kSize);
  auto hill = [](double x, double y) {
    return 30.0 + 25.0 * std::exp(-std::pow((x - 100.0) / 30.0, 2.0)) + 0.01 * y;
  };
  const Raster<float> before = test::heights_from(grid, hill);
  const std::vector<TerrainFeature> features = road_with(Structure::tunnel);
  const TerrainPlan plan = plan_terrain(before, grid, features, {});
  expect_straight_deck(plan);
  Raster<float> h = before;
  apply_terrain(h, grid, Window::whole(grid), plan);
  int untouched = 0;
  for (int col = 0; col < kSize; ++col)
    for (int row = 0; row < kSize; ++row) {
      const Vec2 p = grid.pixel_centre_world(col, row);
      if (p.x < 75.0 || p.x > 125.0) continue;  // beyond the approaches' reach
      EXPECT_EQ(h.at(col, row), before.at(col, row)) << col << " " << row;
      ++untouched;
    }
  EXPECT_EQ(untouched, 50 * kSize);
  // The deck runs under the hill: the tunnel floor at its middle is far below the crest.
  std::size_t s = 0;
  by_fid(plan, 2, &s);
  EXPECT_LT(plan.profiles[s][plan.profiles[s].size() / 2], before.at(100, kRoadRow) - 10.0f);
  const SplatLayers splat = compute_splat(grid, Window::whole(grid), features, {});
  EXPECT_EQ(splat.weights[1].at(100, kRoadRow), 0.0f);
  EXPECT_FLOAT_EQ(splat.weights[0].at(100, kRoadRow), 1.0f);  // base
}

TEST(Structures, ABridgeSplitIntoTwoWaysIsOneStraightDeck) {
  const GridSpec grid = test::unit_grid(kSize);
  auto valley = [](double x, double y) { return 40.0 + 0.3 * std::abs(x - 100.5) + 0.1 * y; };
  const Raster<float> before = test::heights_from(grid, valley);
  std::vector<TerrainFeature> features = road_with(Structure::bridge);
  // Way 2 now ends mid-span, and way 4 continues it, drawn backwards (east to west).
  features[1].centerline.points = {{60.0, 100.5}, {100.0, 100.5}};
  TerrainFeature second = features[1];
  second.fid = 4;
  second.centerline.points = {{140.0, 100.5}, {100.0, 100.5}};
  features.push_back(second);
  const TerrainPlan plan = plan_terrain(before, grid, features, {});
  std::size_t a = 0, s = 0, t = 0, b = 0;
  by_fid(plan, 1, &a);
  by_fid(plan, 2, &s);
  by_fid(plan, 4, &t);
  by_fid(plan, 3, &b);
  const double west = plan.profiles[a].back(), east = plan.profiles[b].front();
  EXPECT_FLOAT_EQ(plan.profiles[s].front(), float(west));
  EXPECT_FLOAT_EQ(plan.profiles[t].front(), float(east));
  // Mid-span both ways hold the middle of the straight deck, not the valley floor below.
  const float middle = float(0.5 * (west + east));
  EXPECT_NEAR(plan.profiles[s].back(), middle, 1e-4);
  EXPECT_NEAR(plan.profiles[t].back(), middle, 1e-4);
  EXPECT_GT(middle, before.at(100, kRoadRow) + 5.0f);
}

}  // namespace
}  // namespace tw
