#include "terrain/splat.hpp"

#include <gtest/gtest.h>

#include "terrain_test_support.hpp"

namespace tw {
namespace {

int channel(const SplatLayers& s, const std::string& name) {
  for (std::size_t i = 0; i < s.materials.size(); ++i)
    if (s.materials[i] == name) return int(i);
  ADD_FAILURE() << "no material " << name;
  return 0;
}

TEST(Splat, WeightsSumToOneAndEdgesAreAntiAliased) {
  const GridSpec grid = test::unit_grid(120);
  std::vector<TerrainFeature> features = {
      test::feature(FeatureKind::road, 1, {{5.0, 40.3}, {115.0, 62.7}}, 6.0),
      test::feature(FeatureKind::river, 2, {{60.2, 5.0}, {50.0, 115.0}}, 8.0),
      test::feature(FeatureKind::ridge, 3, {{10.0, 100.0}, {110.0, 95.0}}, 3.0)};
  const Window window{3, 7, 110, 100};
  const SplatLayers s = compute_splat(grid, window, features, {});
  ASSERT_EQ(s.materials, splat_materials());
  ASSERT_EQ(s.weights.size(), s.materials.size());
  int partial_road = 0, full_road = 0, bank = 0, rock = 0;
  for (int r = 0; r < window.height; ++r)
    for (int c = 0; c < window.width; ++c) {
      float sum = 0.0f;
      for (const auto& w : s.weights) {
        EXPECT_GE(w.at(c, r), 0.0f);
        EXPECT_LE(w.at(c, r), 1.0f);
        sum += w.at(c, r);
      }
      EXPECT_NEAR(sum, 1.0f, 1e-6f) << c << " " << r;
      const float road = s.weights[channel(s, "road")].at(c, r);
      partial_road += road > 0.05f && road < 0.95f;
      full_road += road == 1.0f;
      bank += s.weights[channel(s, "bank")].at(c, r) > 0.5f;
      rock += s.weights[channel(s, "ridge_rock")].at(c, r) > 0.5f;
    }
  EXPECT_GT(partial_road, 100);  // both edges of a 110 m road are ramps
  EXPECT_GT(full_road, 300);
  EXPECT_GT(bank, 100);
  EXPECT_GT(rock, 100);
  // Far from everything: base only. On the road's centre away from the river: road only.
  EXPECT_EQ(s.weights[channel(s, "base")].at(20 - window.col0, 100 - window.row0), 1.0f);
  const Vec2 on_road = grid.world_to_pixel({20.0, 40.3 + 15.0 * 22.4 / 110.0});
  EXPECT_EQ(
      s.weights[channel(s, "road")].at(int(on_road.x) - window.col0, int(on_road.y) - window.row0),
      1.0f);
}

TEST(Splat, RoadOverRiverByDefaultPrecedence) {
  const GridSpec grid = test::unit_grid(100);
  std::vector<TerrainFeature> features = {
      test::feature(FeatureKind::road, 1, {{50.5, 5.0}, {50.5, 95.0}}, 6.0),
      test::feature(FeatureKind::river, 2, {{5.0, 50.5}, {95.0, 50.5}}, 6.0)};
  const SplatLayers s = compute_splat(grid, Window::whole(grid), features, {});
  EXPECT_EQ(s.weights[channel(s, "road")].at(50, 49), 1.0f);
  EXPECT_EQ(s.weights[channel(s, "riverbed")].at(50, 49), 0.0f);
  EXPECT_EQ(s.weights[channel(s, "riverbed")].at(20, 49), 1.0f);
}

}  // namespace
}  // namespace tw
