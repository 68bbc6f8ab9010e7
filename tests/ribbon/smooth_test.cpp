// smooth(): arc-length Gaussian smoothing with fixed ends.
#include "ribbon/smooth.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace tw {
namespace {

TEST(Smooth, StraightLineStaysOnTheLineWithEndsFixed) {
  const Curve line{{{0, 0}, {30, 40}, {60, 80}}, false};
  const Curve s = smooth(line, 5.0);
  ASSERT_GT(s.points.size(), 10u);
  EXPECT_EQ(s.points.front(), line.points.front());
  EXPECT_EQ(s.points.back(), line.points.back());
  for (const Vec2 p : s.points) EXPECT_NEAR(cross(normalized(Vec2{3, 4}), p), 0.0, 1e-9);
  EXPECT_NEAR(arc_length(s), 100.0, 1e-9);
}

TEST(Smooth, ReducesZigzagNoise) {
  Curve zigzag;
  for (int i = 0; i <= 100; ++i) zigzag.points.push_back({double(i), (i % 2) ? 0.5 : -0.5});
  const Curve s = smooth(zigzag, 3.0);
  EXPECT_EQ(s.points.front(), zigzag.points.front());
  EXPECT_EQ(s.points.back(), zigzag.points.back());
  double worst = 0.0;
  for (const Vec2 p : s.points)
    if (p.x > 10.0 && p.x < 90.0) worst = std::max(worst, std::abs(p.y));
  EXPECT_LT(worst, 0.02);  // from +-0.5 m
}

TEST(Smooth, ClosedCircleStaysACircle) {
  Curve circle;
  circle.closed = true;
  for (int k = 0; k < 64; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 64;
    circle.points.push_back({100.0 * std::cos(a), 100.0 * std::sin(a)});
  }
  const Curve s = smooth(circle, 4.0);
  EXPECT_TRUE(s.closed);
  for (const Vec2 p : s.points) EXPECT_NEAR(length(p), 100.0, 0.2);
}

TEST(Smooth, SharpCornerIsRounded) {
  const Curve corner{{{0, 0}, {50, 0}, {50, 50}}, false};
  const Curve s = smooth(corner, 5.0);
  double closest = 1e9;
  for (const Vec2 p : s.points) closest = std::min(closest, distance(p, {50, 0}));
  EXPECT_GT(closest, 1.0);  // the corner is cut
  EXPECT_LT(closest, 5.0);  // but only locally
}

TEST(Smooth, ZeroWindowIsIdentityAndNanThrows) {
  const Curve c{{{0, 0}, {1, 2}, {3, 1}}, false};
  EXPECT_EQ(smooth(c, 0.0).points, c.points);
  EXPECT_THROW(smooth(c, std::nan("")), Error);
}

}  // namespace
}  // namespace tw
