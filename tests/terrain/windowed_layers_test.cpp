// Terrain on a window: apply_terrain and compute_splat given heights that cover only the window
// equal the same window of a whole-grid call, bit for bit; add_pattern_to_layers takes its
// share from every material and leaves nodata alone.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/error.hpp"
#include "terrain/height_ops.hpp"
#include "terrain/pattern_layers.hpp"
#include "terrain/splat.hpp"
#include "terrain_test_support.hpp"

namespace tw {
namespace {

Raster<float> crop(const Raster<float>& whole, const Window& w) {
  Raster<float> out(w.width, w.height);
  for (int row = 0; row < w.height; ++row)
    for (int col = 0; col < w.width; ++col) out.at(col, row) = whole.at(w.col0 + col, w.row0 + row);
  return out;
}

bool same_bits(const Raster<float>& a, const Raster<float>& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

TEST(WindowedTerrain, WindowSizedHeightsEqualTheWholeGridsWindow) {
  const GridSpec grid = test::unit_grid(160);
  Raster<float> before =
      test::heights_from(grid, [](double x, double y) { return 50.0 + 0.2 * x + 0.05 * y; });
  before.at(70, 70) = NAN;  // nodata stays nodata, and gets no splat
  std::vector<TerrainFeature> features = {
      test::feature(FeatureKind::road, 1, {{5, 20}, {80, 90}, {155, 150}}, 6.0),
      test::feature(FeatureKind::river, 2, {{0, 100}, {160, 60}}, 8.0)};
  const TerrainPlan plan = plan_terrain(before, grid, features, {});
  Raster<float> whole = before;
  apply_terrain(whole, grid, Window::whole(grid), plan);
  const SplatLayers whole_splat = compute_splat(grid, Window::whole(grid), features, {}, whole);
  for (const Window w : {Window{37, 41, 53, 29}, Window{60, 60, 100, 100}, Window{0, 0, 1, 1}}) {
    Raster<float> part = crop(before, w);
    apply_terrain(part, grid, w, plan);
    EXPECT_TRUE(same_bits(part, crop(whole, w)));
    const SplatLayers splat = compute_splat(grid, w, features, {}, part);
    for (std::size_t m = 0; m < splat.weights.size(); ++m)
      EXPECT_TRUE(same_bits(splat.weights[m], crop(whole_splat.weights[m], w))) << m;
  }
  EXPECT_NE(whole.at(80, 70), before.at(80, 70));  // the road did change heights
  Raster<float> wrong(10, 10);
  EXPECT_THROW(apply_terrain(wrong, grid, Window{0, 0, 20, 20}, plan), Error);
}

TEST(PatternLayers, ASplatShareComesFromEveryMaterialAndHeightAddsDetail) {
  const Window window{10, 10, 4, 1};
  Raster<float> height(4, 1, 100.0f);
  height.at(3, 0) = NAN;
  SplatLayers splat;
  splat.materials = {"base", "road", "cobble"};
  splat.weights = {Raster<float>(4, 1, 0.5f), Raster<float>(4, 1, 0.5f), Raster<float>(4, 1, 0.0f)};
  const Window part{11, 10, 3, 1};
  Raster<float> coverage(3, 1, 0.5f);
  coverage.at(0, 0) = 0.0f;
  const Raster<float> detail(3, 1, 2.0f);
  add_pattern_to_layers(window, height, splat, part, coverage,
                        {{&coverage, false, 2, true}, {&detail, true, 0, false}}, 1.5f);
  EXPECT_EQ(height.at(0, 0), 100.0f);  // outside the part
  EXPECT_EQ(height.at(1, 0), 100.0f);  // no coverage
  EXPECT_EQ(height.at(2, 0), 100.0f + 1.5f * 2.0f * 0.5f);
  EXPECT_TRUE(std::isnan(height.at(3, 0)));
  EXPECT_EQ(splat.weights[0].at(2, 0), 0.25f);
  EXPECT_EQ(splat.weights[1].at(2, 0), 0.25f);
  EXPECT_EQ(splat.weights[2].at(2, 0), 0.5f);
  EXPECT_EQ(splat.weights[2].at(3, 0), 0.0f);  // nothing painted on nodata
  EXPECT_THROW(add_pattern_to_layers(window, height, splat, {8, 10, 3, 1}, coverage, {}, 1.0f),
               Error);
}

}  // namespace
}  // namespace tw
