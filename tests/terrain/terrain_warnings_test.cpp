// What the terrain stage warns about: a feature on the grid that lies only over nodata is left
// out, named by its class and FID.
#include <gtest/gtest.h>

#include <limits>

#include "terrain/height_ops.hpp"
#include "terrain_test_support.hpp"

namespace tw {
namespace {

TEST(TerrainWarnings, AFeatureOverNodataIsLeftOutWithAWarning) {
  const GridSpec grid = test::unit_grid(100);
  Raster<float> h = test::heights_from(grid, [](double, double) { return 50.0; });
  for (int row = 0; row < 100; ++row)
    for (int col = 0; col < 40; ++col) h.at(col, row) = std::numeric_limits<float>::quiet_NaN();
  const Raster<float> before = h;
  auto over_nodata = test::feature(FeatureKind::river, 7, {{5.0, 50.5}, {35.0, 50.5}}, 4.0);
  over_nodata.subject = "features.rivers";
  auto on_terrain = test::feature(FeatureKind::river, 8, {{45.0, 20.5}, {95.0, 20.5}}, 4.0);
  on_terrain.subject = "features.rivers";
  auto off_grid = test::feature(FeatureKind::road, 9, {{150.0, 20.5}, {190.0, 20.5}}, 4.0);
  Warnings warnings;
  shape_terrain(h, grid, Window::whole(grid), {over_nodata, on_terrain, off_grid}, {}, warnings);
  ASSERT_EQ(warnings.size(), 1u);
  const Warning w = warnings.list()[0];
  EXPECT_EQ(w.code, "over_nodata");
  EXPECT_EQ(w.subject, "features.rivers");
  EXPECT_EQ(w.fid, 7);
  // The river on the terrain is carved; nothing is written into nodata.
  EXPECT_LT(h.at(70, 100 - 21), before.at(70, 100 - 21) - 0.5);
  for (int row = 0; row < 100; ++row)
    for (int col = 0; col < 40; ++col) EXPECT_TRUE(std::isnan(h.at(col, row)));
}

}  // namespace
}  // namespace tw
