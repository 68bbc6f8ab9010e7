#include "terrain/ribbon_frame.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "terrain_test_support.hpp"

namespace tw {
namespace {

TEST(RibbonFrame, StraightLineGivesAlongAndSignedAcross) {
  const GridSpec grid = test::unit_grid(100);
  const Curve line{{{10.0, 50.0}, {90.0, 50.0}}, false};  // eastwards along world y = 50
  const RibbonFrame frame = compute_ribbon_frame(grid, Window::whole(grid), line, 5.0);
  // Row 49 has centres at y = 50.5: north of an eastward curve is its left (positive).
  EXPECT_FLOAT_EQ(frame.along.at(40, 49), 30.5f);
  EXPECT_FLOAT_EQ(frame.across.at(40, 49), 0.5f);
  EXPECT_FLOAT_EQ(frame.across.at(40, 52), -2.5f);
  EXPECT_TRUE(std::isnan(frame.along.at(40, 40)));  // 9.5 m away, beyond reach
  // Beyond the end the nearest point is the end itself.
  EXPECT_FLOAT_EQ(frame.along.at(92, 49), 80.0f);
  EXPECT_NEAR(frame.across.at(92, 49), std::hypot(2.5, 0.5), 1e-5);
}

TEST(RibbonFrame, MatchesBruteForceOnAWindowOfABentCurve) {
  const GridSpec grid = test::unit_grid(120);
  const Curve curve{{{5.0, 5.0}, {60.0, 70.3}, {110.0, 40.0}, {100.0, 110.0}}, false};
  const Window window{17, 9, 90, 100};
  const double reach = 12.0;
  const RibbonFrame frame = compute_ribbon_frame(grid, window, curve, reach);
  ASSERT_EQ(frame.along.width, window.width);
  int inside = 0;
  for (int r = 0; r < window.height; ++r)
    for (int c = 0; c < window.width; ++c) {
      const Vec2 p = grid.pixel_centre_world(window.col0 + c, window.row0 + r);
      double best = std::numeric_limits<double>::infinity(), along = 0, s = 0;
      for (std::size_t i = 0; i + 1 < curve.points.size(); ++i) {
        const Vec2 a = curve.points[i], ab = curve.points[i + 1] - a;
        const double t = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
        const double d = distance(p, a + ab * t);
        if (d < best) best = d, along = s + t * length(ab);
        s += length(ab);
      }
      if (best > reach) {
        EXPECT_TRUE(std::isnan(frame.along.at(c, r)));
        continue;
      }
      ++inside;
      EXPECT_NEAR(std::abs(frame.across.at(c, r)), best, 1e-4);
      EXPECT_NEAR(frame.along.at(c, r), along, 1e-3);
    }
  EXPECT_GT(inside, 1000);
}

}  // namespace
}  // namespace tw
