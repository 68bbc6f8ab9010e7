// find_junctions: shared endpoints, T-junctions, crossings, self-crossings.
#include "ribbon/junctions.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/error.hpp"

namespace tw {
namespace {

TEST(Junctions, XCrossingBetweenTwoCurves) {
  const std::vector<Curve> curves{{{{0, 0}, {10, 10}}, false}, {{{0, 10}, {4, 6}, {10, 0}}, false}};
  const auto js = find_junctions(curves, 0.01);
  ASSERT_EQ(js.size(), 1u);
  EXPECT_TRUE(js[0].crossing);
  EXPECT_NEAR(js[0].position.x, 5.0, 1e-9);
  EXPECT_NEAR(js[0].position.y, 5.0, 1e-9);
  ASSERT_EQ(js[0].members.size(), 2u);
  EXPECT_EQ(js[0].members[0].curve, 0u);
  EXPECT_NEAR(js[0].members[0].arc_length, std::sqrt(50.0), 1e-9);
  EXPECT_FALSE(js[0].members[0].at_endpoint);
  EXPECT_EQ(js[0].members[1].curve, 1u);
  EXPECT_NEAR(js[0].members[1].arc_length, std::sqrt(50.0), 1e-9);
}

TEST(Junctions, SharedEndpointsWithinToleranceMerge) {
  const std::vector<Curve> curves{{{{0, 0}, {10, 0}}, false},
                                  {{{10.05, 0.02}, {20, 5}}, false},
                                  {{{9.98, -0.03}, {10, -10}}, false}};
  const auto js = find_junctions(curves, 0.1);
  ASSERT_EQ(js.size(), 1u);
  EXPECT_FALSE(js[0].crossing);
  ASSERT_EQ(js[0].members.size(), 3u);
  for (const auto& m : js[0].members) EXPECT_TRUE(m.at_endpoint);
  EXPECT_DOUBLE_EQ(js[0].members[0].arc_length, 10.0);
  EXPECT_DOUBLE_EQ(js[0].members[1].arc_length, 0.0);
  EXPECT_NEAR(js[0].position.x, 10.0, 0.1);
  // Apart by more than the tolerance: nothing.
  EXPECT_TRUE(find_junctions(curves, 0.01).empty());
}

TEST(Junctions, TJunctionHasOneMemberPassingThrough) {
  const std::vector<Curve> curves{{{{0, 0}, {20, 0}}, false}, {{{8, 10}, {8, 0.05}}, false}};
  const auto js = find_junctions(curves, 0.1);
  ASSERT_EQ(js.size(), 1u);
  EXPECT_FALSE(js[0].crossing);
  EXPECT_EQ(js[0].members[0].curve, 0u);
  EXPECT_NEAR(js[0].members[0].arc_length, 8.0, 1e-9);
  EXPECT_FALSE(js[0].members[0].at_endpoint);
  EXPECT_TRUE(js[0].members[1].at_endpoint);
}

TEST(Junctions, SelfCrossingLoopButNotNeighbouringSegments) {
  const Curve loop{{{0, 0}, {10, 0}, {10, 10}, {5, 10}, {5, -5}}, false};
  const auto js = find_junctions({loop}, 1e-6);
  ASSERT_EQ(js.size(), 1u);
  EXPECT_TRUE(js[0].crossing);
  EXPECT_NEAR(js[0].position.x, 5.0, 1e-9);
  EXPECT_NEAR(js[0].position.y, 0.0, 1e-9);
  ASSERT_EQ(js[0].members.size(), 2u);
  EXPECT_NEAR(js[0].members[0].arc_length, 5.0, 1e-9);
  EXPECT_NEAR(js[0].members[1].arc_length, 35.0, 1e-9);
  // A closed square touches itself only through neighbouring segments: no junction.
  EXPECT_TRUE(find_junctions({Curve{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, true}}, 1e-6).empty());
}

TEST(Junctions, GridOfStreetsMatchesBruteForceCount) {
  // 12 horizontal and 9 vertical wiggly streets, many vertices each: 108 crossings.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<Curve> curves;
  for (int i = 0; i < 12; ++i) {
    Curve c;
    for (int k = 0; k <= 200; ++k) c.points.push_back({k * 1.0 - 5.0, i * 10.0 + 3 + jitter(rng)});
    curves.push_back(c);
  }
  for (int i = 0; i < 9; ++i) {
    Curve c;
    for (int k = 0; k <= 150; ++k) c.points.push_back({i * 20.0 + 7 + jitter(rng), k * 1.0 - 5.0});
    curves.push_back(c);
  }
  const auto js = find_junctions(curves, 1e-6);
  EXPECT_EQ(js.size(), 108u);
  for (const auto& j : js) {
    EXPECT_TRUE(j.crossing);
    ASSERT_EQ(j.members.size(), 2u);
    EXPECT_LT(j.members[0].curve, 12u);
    EXPECT_GE(j.members[1].curve, 12u);
  }
  EXPECT_EQ(find_junctions(curves, 1e-6).size(), js.size());  // deterministic
}

TEST(Junctions, RejectsBadInput) {
  EXPECT_THROW(find_junctions({}, -1.0), Error);
  EXPECT_THROW(find_junctions({Curve{{{0, 0}, {std::nan(""), 1}}, false}}, 0.1), Error);
  EXPECT_TRUE(find_junctions({}, 0.1).empty());
}

// Vertices 125 times closer than the tolerance (a 5000-vertex line over 20 m with a
// 0.5 m tolerance), crossed by one long diagonal segment and met by a T: the same junctions as
// with two vertices (the crossing test no longer compares every pair of segments within a
// tolerance-sized cell, which took minutes at 100 000 vertices) and the T has one member on the
// dense line, at its closest point (it had two, a "crossing").
TEST(Junctions, DenseVerticesFindTheSameJunctionsAsSparseOnes) {
  Curve dense{{}, false};
  for (int i = 0; i <= 5000; ++i) dense.points.push_back({-10.0 + 20.0 * i / 5000, 0.0});
  const Curve sparse{{{-10, 0}, {10, 0}}, false};
  const Curve diagonal{{{-1000, -999.01}, {20, 20.99}}, false};  // y = 0 at x = -0.99
  const Curve t{{{5, 0.2}, {5, 3}}, false};
  for (const Curve& line : {sparse, dense}) {
    const auto js = find_junctions({line, diagonal, t}, 0.5);
    ASSERT_EQ(js.size(), 2u) << line.points.size();
    EXPECT_TRUE(js[0].crossing);
    EXPECT_NEAR(js[0].position.x, -0.99, 1e-9);
    EXPECT_NEAR(js[0].position.y, 0.0, 1e-9);
    EXPECT_NEAR(js[0].members[0].arc_length, 9.01, 1e-9);
    EXPECT_FALSE(js[1].crossing);
    EXPECT_NEAR(js[1].members[0].arc_length, 15.0, 1e-9);
    EXPECT_EQ(js[1].members[1].curve, 2u);
  }
}

}  // namespace
}  // namespace tw
