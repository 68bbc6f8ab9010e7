// update_junctions: after some curves changed, the junctions of a whole search, found near the
// change alone.
#include "ribbon/junction_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.hpp"

namespace tw {
namespace {

// Bit for bit: positions, members and extents compared with ==, in order.
void expect_same_search(const JunctionSearch& a, const JunctionSearch& b) {
  ASSERT_EQ(a.junctions.size(), b.junctions.size());
  for (std::size_t j = 0; j < a.junctions.size(); ++j) {
    EXPECT_EQ(a.junctions[j].position, b.junctions[j].position) << j;
    EXPECT_EQ(a.junctions[j].members, b.junctions[j].members) << j;
    EXPECT_EQ(a.junctions[j].crossing, b.junctions[j].crossing) << j;
  }
  EXPECT_EQ(a.extents, b.extents);
  EXPECT_EQ(a.boxes, b.boxes);
}

// A street grid of blocks of 100 m: streets two blocks long, jittered, ending on or near other
// streets (T-junctions, shared ends) and crossing them.
std::vector<Curve> jittered_streets(std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(-3.0, 3.0);
  std::vector<Curve> curves;
  for (int k = 0; k < 8; ++k) {
    for (int i = k % 2; i < 8; i += 2) {
      Curve across, up;
      for (int s = 0; s <= 2; ++s) {
        across.points.push_back({(i + s) * 100.0 + jitter(rng), k * 100.0 + jitter(rng)});
        up.points.push_back({k * 100.0 + jitter(rng), (i + s) * 100.0 + jitter(rng)});
      }
      curves.push_back(across);
      curves.push_back(up);
    }
  }
  return curves;
}

TEST(JunctionSearch, AMovedCurveIsSearchedNearItAloneAndGivesTheWholeSearch) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> offset(-15.0, 15.0);
  std::vector<Curve> curves = jittered_streets(rng);
  JunctionSearch search = search_junctions(curves, 2.0);
  ASSERT_GT(search.junctions.size(), 60u);
  for (int step = 0; step < 16; ++step) {
    std::vector<bool> changed(curves.size(), false);
    const std::size_t moved = rng() % curves.size();
    changed[moved] = true;
    const Vec2 by{offset(rng), offset(rng)};
    for (Vec2& p : curves[moved].points) p += by;
    search = update_junctions(search, curves, changed);
    expect_same_search(search, search_junctions(curves, 2.0));
    EXPECT_LT(search.curves_searched, curves.size() / 4) << step;
  }
}

TEST(JunctionSearch, AMovedCurveGainsAndLosesAJunctionWithANeighbour) {
  // c0 and c1 meet at (50, 0); c2 ends 5 m short of c0, then on it (a T-junction), then off.
  std::vector<Curve> curves{{{{0, 0}, {100, 0}}, false},
                            {{{50, -50}, {50, 50}}, false},
                            {{{20, 5}, {20, 40}}, false},
                            {{{300, 300}, {400, 300}}, false}};
  const std::vector<bool> changed{false, false, true, false};
  const JunctionSearch first = search_junctions(curves, 1.0);
  ASSERT_EQ(first.junctions.size(), 1u);
  for (Vec2& p : curves[2].points) p.y -= 5.0;  // now ends on c0
  const JunctionSearch gained = update_junctions(first, curves, changed);
  expect_same_search(gained, search_junctions(curves, 1.0));
  ASSERT_EQ(gained.junctions.size(), 2u);
  EXPECT_EQ(gained.junctions[0].members[0].curve, 0u);
  EXPECT_EQ(gained.junctions[0].members[1].curve, 2u);
  EXPECT_LT(gained.curves_searched, curves.size());
  for (Vec2& p : curves[2].points) p.y += 7.0;  // off again
  const JunctionSearch lost = update_junctions(gained, curves, changed);
  expect_same_search(lost, search_junctions(curves, 1.0));
  EXPECT_EQ(lost.junctions.size(), 1u);
}

TEST(JunctionSearch, AJunctionMergedWithAMovedEndIsFoundWhole) {
  // c0, c1 cross at (50, 0); c2's end comes within the tolerance of that crossing: one junction
  // of three, then of two again when it leaves.
  std::vector<Curve> curves{{{{0, 0}, {100, 0}}, false},
                            {{{50, -50}, {50, 50}}, false},
                            {{{51.5, 1.5}, {90, 60}}, false},
                            {{{-300, 0}, {-200, 0}}, false},
                            {{{-300, 50}, {-200, 50}}, false}};
  const std::vector<bool> changed{false, false, true, false, false};
  const JunctionSearch far = search_junctions(curves, 1.0);
  for (Vec2& p : curves[2].points) p += Vec2{-1.0, -1.0};
  const JunctionSearch merged = update_junctions(far, curves, changed);
  expect_same_search(merged, search_junctions(curves, 1.0));
  ASSERT_EQ(merged.junctions.size(), 1u);
  EXPECT_EQ(merged.junctions[0].members.size(), 3u);
  for (Vec2& p : curves[2].points) p += Vec2{1.0, 1.0};
  expect_same_search(update_junctions(merged, curves, changed), far);
}

TEST(JunctionSearch, AChangedCurveThatIsNotFiniteIsTheWholeSearchsError) {
  std::vector<Curve> curves{{{{0, 0}, {10, 0}}, false}, {{{5, -5}, {5, 5}}, false}};
  const JunctionSearch first = search_junctions(curves, 0.5);
  curves[1].points[1].y = std::nan("");
  EXPECT_THROW(update_junctions(first, curves, {false, true}), Error);
}

TEST(JunctionSearch, ACountThatDiffersSearchesEveryCurve) {
  const std::vector<Curve> curves{{{{0, 0}, {10, 0}}, false}, {{{5, -5}, {5, 5}}, false}};
  const JunctionSearch one = search_junctions({curves[0]}, 0.5);
  const JunctionSearch both = update_junctions(one, curves, {false, true});
  expect_same_search(both, search_junctions(curves, 0.5));
  EXPECT_EQ(both.curves_searched, 2u);
}

}  // namespace
}  // namespace tw
