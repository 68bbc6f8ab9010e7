// make_ribbon: the pieces are the paper's quadrilaterals T(x_i), B(x_i), B(x_i+1), T(x_i+1).
#include "ribbon/ribbon.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace tw {
namespace {

void expect_near(Vec2 a, Vec2 b, double tol = 1e-9) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
}

TEST(Ribbon, StraightLinePiecesIncludingFractionalLast) {
  const Curve line{{{0, 0}, {10, 0}}, false};
  const Ribbon r = make_ribbon(line, {4.0, 3.0});
  ASSERT_EQ(r.pieces.size(), 4u);  // 3 + 3 + 3 + 1
  for (std::size_t i = 0; i < 3; ++i) {
    const Piece& p = r.pieces[i];
    expect_near(p.top_left, {3.0 * i, 2.0});
    expect_near(p.bottom_left, {3.0 * i, -2.0});
    expect_near(p.bottom_right, {3.0 * (i + 1), -2.0});
    expect_near(p.top_right, {3.0 * (i + 1), 2.0});
    EXPECT_DOUBLE_EQ(p.x1 - p.x0, 3.0);
    expect_near(p.l(), {0, -4});
    expect_near(p.t(), {3, 0});
    expect_near(p.d(), {3, -4});
  }
  const Piece& last = r.pieces.back();
  EXPECT_DOUBLE_EQ(last.x0, 9.0);
  EXPECT_DOUBLE_EQ(last.x1, 10.0);
  expect_near(last.top_right, {10.0, 2.0});
  expect_near(last.bottom_right, {10.0, -2.0});
}

TEST(Ribbon, OffsetsAreExactlyHalfWidthAlongTheNormal) {
  // A circle of radius 50 m: every T and B is at radius 50 -+ b/2 (left is the inside of a
  // counter-clockwise walk).
  Curve circle;
  circle.closed = true;
  for (int k = 0; k < 720; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 720;
    circle.points.push_back({50.0 * std::cos(a), 50.0 * std::sin(a)});
  }
  const Ribbon r = make_ribbon(circle, {6.0, 5.0});
  for (const Piece& p : r.pieces) {
    EXPECT_NEAR(distance(p.top_left, p.bottom_left), 6.0, 1e-9);
    const Vec2 c = (p.top_left + p.bottom_left) / 2.0;
    EXPECT_NEAR(length(c), 50.0, 0.01);
    EXPECT_NEAR(length(p.top_left), 47.0, 0.01);
    EXPECT_NEAR(length(p.bottom_left), 53.0, 0.01);
  }
}

TEST(Ribbon, ClosedRibbonWrapsLastPieceOntoFirst) {
  const Curve square{{{0, 0}, {20, 0}, {20, 20}, {0, 20}}, true};
  const Ribbon r = make_ribbon(square, {2.0, 7.0});
  EXPECT_TRUE(r.closed);
  ASSERT_EQ(r.pieces.size(), 12u);  // ceil(80 / 7)
  EXPECT_EQ(r.pieces.back().top_right, r.pieces.front().top_left);
  EXPECT_EQ(r.pieces.back().bottom_right, r.pieces.front().bottom_left);
  EXPECT_DOUBLE_EQ(r.pieces.back().x1, 80.0);
  for (std::size_t i = 0; i + 1 < r.pieces.size(); ++i) {
    EXPECT_EQ(r.pieces[i].top_right, r.pieces[i + 1].top_left);
    EXPECT_EQ(r.pieces[i].bottom_right, r.pieces[i + 1].bottom_left);
  }
}

TEST(Ribbon, RejectsBadParameters) {
  const Curve line{{{0, 0}, {10, 0}}, false};
  EXPECT_THROW(make_ribbon(line, {0.0, 1.0}), Error);
  EXPECT_THROW(make_ribbon(line, {1.0, -1.0}), Error);
  EXPECT_THROW(make_ribbon(line, {1.0, 11.0}), Error);
  EXPECT_THROW(make_ribbon(Curve{{{1, 1}, {1, 1}}, false}, {1.0, 1.0}), Error);
}

}  // namespace
}  // namespace tw
