// Bends as the exemplar's (docs/networks.md, "Growth" 8 and 12): where the exemplar's edges are
// nearly all straight, a chord replacing a bent output edge meets the lines at its junctions no
// more narrowly than the exemplar's lines meet, and the bends left turn per metre as the
// exemplar's own few bends (its frame's corners) do.
#include <gtest/gtest.h>

#include "network/check.hpp"
#include "network/growth.hpp"
#include "network/stats.hpp"
#include "network_fixtures.hpp"

namespace tw {
namespace {

constexpr int kBendCurvature = 2;
constexpr int kBendJunctionAngle = 3;

// The bench's bocage (285 edges, all straight but its frame's 4 corners, turning 0.0065 to
// 0.0114 rad/m): before, the bends left at seeds 1-3 (5, 5 and 3 edges no chord, removal or link
// could undo) turned up to 0.026 rad/m, and its curvature distance was 0.066, 0.110, 0.089
// against a bound of 0.05 (halves 0.014; an output with no bend at all: 0.116, the baseline's).
TEST(NetworkBends, BocageBendsTurnPerMetreAsItsFrameCornersDo) {
  const Network bocage = test::bench_exemplar("bocage");
  for (std::uint64_t seed : {1, 2, 3}) test::expect_target_met(bocage, kBendCurvature, seed);
}

// Its lines meet at 52° or more (Ts and the fields' slanted sides); a corner's chord turned up
// to 57° off its old heading made Ys of 30° to 45° among them. Before, its junction angles at
// seed 2 were 0.054 from the exemplar's against a bound of 0.05 (halves 0.021).
TEST(NetworkBends, BocageChordsMeetItsLinesNoMoreNarrowlyThanItsOwnDo) {
  test::expect_target_met(test::bench_exemplar("bocage"), kBendJunctionAngle, 2);
}

}  // namespace
}  // namespace tw
