// Arc length, cumulative lengths, point/tangent lookup and resampling of polylines.
#include "ribbon/curve.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace tw {
namespace {

Curve square(double side, bool closed) {
  return {{{0, 0}, {side, 0}, {side, side}, {0, side}}, closed};
}

TEST(Curve, ArcLengthOpenAndClosed) {
  EXPECT_DOUBLE_EQ(arc_length(square(2.0, false)), 6.0);
  EXPECT_DOUBLE_EQ(arc_length(square(2.0, true)), 8.0);
  EXPECT_DOUBLE_EQ(arc_length(Curve{{{0, 0}, {3, 4}}, false}), 5.0);
}

TEST(Curve, CumulativeLengthsHaveOneMoreEntryWhenClosed) {
  const auto open = cumulative_lengths(square(1.0, false));
  const auto closed = cumulative_lengths(square(1.0, true));
  ASSERT_EQ(open.size(), 4u);
  ASSERT_EQ(closed.size(), 5u);
  EXPECT_DOUBLE_EQ(open[2], 2.0);
  EXPECT_DOUBLE_EQ(closed[4], 4.0);
}

TEST(Curve, PointAtClampsOpenAndWrapsClosed) {
  const Curve open = square(1.0, false);
  const Curve closed = square(1.0, true);
  const auto co = cumulative_lengths(open);
  const auto cc = cumulative_lengths(closed);
  EXPECT_EQ(point_at(open, co, 1.5), (Vec2{1.0, 0.5}));
  EXPECT_EQ(point_at(open, co, -3.0), (Vec2{0.0, 0.0}));
  EXPECT_EQ(point_at(open, co, 99.0), (Vec2{0.0, 1.0}));
  const Vec2 back = point_at(closed, cc, 3.5);  // on the closing edge
  EXPECT_DOUBLE_EQ(back.x, 0.0);
  EXPECT_DOUBLE_EQ(back.y, 0.5);
  const Vec2 wrapped = point_at(closed, cc, 4.25);
  EXPECT_NEAR(wrapped.x, 0.25, 1e-12);
  EXPECT_NEAR(wrapped.y, 0.0, 1e-12);
}

TEST(Curve, TangentAndLeftNormal) {
  const Curve line{{{0, 0}, {10, 0}}, false};
  const auto c = cumulative_lengths(line);
  const Vec2 t = tangent_at(line, c, 5.0, 1.0);
  EXPECT_DOUBLE_EQ(t.x, 1.0);
  EXPECT_DOUBLE_EQ(t.y, 0.0);
  EXPECT_EQ(perp(t), (Vec2{0.0, 1.0}));  // the left of an eastward walk is north
}

TEST(Curve, ResampleKeepsEndsAndSpacesUniformly) {
  const Curve curve{{{0, 0}, {7, 0}, {7, 3}}, false};  // 10 m
  const Curve r = resample(curve, 3.0);
  ASSERT_EQ(r.points.size(), 5u);  // ceil(10 / 3) = 4 segments of 2.5 m
  EXPECT_EQ(r.points.front(), (Vec2{0, 0}));
  EXPECT_EQ(r.points.back(), (Vec2{7, 3}));
  for (std::size_t i = 1; i < r.points.size(); ++i) {
    // Chords at the corner are shorter than the arc length step; elsewhere exact.
    EXPECT_LE(distance(r.points[i - 1], r.points[i]), 2.5 + 1e-12);
  }
  EXPECT_NEAR(r.points[1].x, 2.5, 1e-12);
  EXPECT_NEAR(r.points[3].y, 0.5, 1e-12);
  EXPECT_THROW(resample(curve, 0.0), Error);
}

TEST(Curve, ResampleClosedDoesNotRepeatFirstPoint) {
  const Curve r = resample(square(4.0, true), 1.0);
  ASSERT_EQ(r.points.size(), 16u);
  EXPECT_TRUE(r.closed);
  EXPECT_NEAR(arc_length(r), 16.0, 1e-9);
}

TEST(Curve, WithoutDuplicatesDropsRepeatsAndClosingRepeat) {
  const Curve c{{{0, 0}, {0, 0}, {1, 0}, {1, 1}, {0, 0}}, true};
  const Curve d = without_duplicates(c);
  ASSERT_EQ(d.points.size(), 3u);
  EXPECT_EQ(d.points[2], (Vec2{1, 1}));
}

}  // namespace
}  // namespace tw
