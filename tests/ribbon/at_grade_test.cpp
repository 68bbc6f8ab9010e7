#include <gtest/gtest.h>

#include "ribbon/junctions.hpp"

namespace tw {
namespace {

Curve line(Vec2 a, Vec2 b) {
  return Curve{{a, b}, false};
}

TEST(AtGrade, BridgesTunnelsAndOtherLayersPassWhileEndsStillMeet) {
  const std::vector<Curve> curves = {
      line({0, 0}, {100, 0}),     // 0: a river
      line({50, -20}, {50, 20}),  // 1: a bridge over it
      line({80, -20}, {80, 20}),  // 2: a ford (ground, layer 0): crosses at grade
      line({20, -20}, {20, 20}),  // 3: a road on layer 1 (an embankment mapped as a layer)
      line({50, 20}, {50, 60}),   // 4: the bridge's approach, ending where the bridge ends
      line({35, -30}, {35, 30}),  // 5: a tunnel under the river, on layer -1
  };
  const std::vector<CurveLevel> levels = {{Structure::ground, 0}, {Structure::bridge, 1},
                                          {Structure::ground, 0}, {Structure::ground, 1},
                                          {Structure::ground, 0}, {Structure::tunnel, -1}};
  const std::vector<Junction> all = find_junctions(curves, 0.5);
  ASSERT_EQ(all.size(), 5u);
  const std::vector<Junction> kept = at_grade(all, levels);
  ASSERT_EQ(kept.size(), 2u);
  // The ford crosses the river at x = 80.
  EXPECT_TRUE(kept[0].crossing);
  ASSERT_EQ(kept[0].members.size(), 2u);
  EXPECT_EQ(kept[0].members[0].curve, 0u);
  EXPECT_DOUBLE_EQ(kept[0].members[0].arc_length, 80.0);
  EXPECT_EQ(kept[0].members[1].curve, 2u);
  // The bridge meets its approach end to end, though their layers differ.
  EXPECT_FALSE(kept[1].crossing);
  ASSERT_EQ(kept[1].members.size(), 2u);
  EXPECT_EQ(kept[1].members[0].curve, 1u);
  EXPECT_TRUE(kept[1].members[0].at_endpoint);
  EXPECT_EQ(kept[1].members[1].curve, 4u);
}

TEST(AtGrade, AJunctionSplitsByLayer) {
  // Two roads on layer 1 and two on layer 0 cross at one point: two crossings, not one.
  const std::vector<Curve> curves = {line({-10, 0}, {10, 0}), line({0, -10}, {0, 10}),
                                     line({-10, -10}, {10, 10}), line({-10, 10}, {10, -10})};
  const std::vector<CurveLevel> levels = {{Structure::ground, 0},
                                          {Structure::ground, 0},
                                          {Structure::ground, 1},
                                          {Structure::ground, 1}};
  const std::vector<Junction> all = find_junctions(curves, 0.5);
  ASSERT_EQ(all.size(), 1u);
  ASSERT_EQ(all[0].members.size(), 4u);
  const std::vector<Junction> kept = at_grade(all, levels);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].members[0].curve, 0u);
  EXPECT_EQ(kept[0].members[1].curve, 1u);
  EXPECT_EQ(kept[1].members[0].curve, 2u);
  EXPECT_EQ(kept[1].members[1].curve, 3u);
  EXPECT_TRUE(kept[0].crossing);
  EXPECT_TRUE(kept[1].crossing);
}

}  // namespace
}  // namespace tw
