// Where the exemplar's cells are closed and whole and its edges bend, or its lines end free (a
// forest), junctions are shifted by a few hundredths of a median edge where that brings the
// output's chord bearings nearer the exemplar's (docs/networks.md, "Growth", step 13). The county
// boundaries of North Carolina over their own box: from the quilt (what `automatic` keeps) their
// bearings were 0.064, 0.055, 0.072, 0.095, 0.065 at seeds 3, 4, 6, 9 and 11, each above the
// placement baseline's (0.057, 0.051, 0.066, 0.045, 0.054); growth's 0.063, 0.062, 0.077, 0.096,
// 0.079.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "network/check.hpp"
#include "network/growth.hpp"
#include "network/stats.hpp"
#include "network_fixtures.hpp"

namespace tw {
namespace {

constexpr int kShiftBearing = 5;

TEST(NetworkJunctionShift, CountyBearingsBeatThePlacementBaselineWhereTheyMissedIt) {
  ASSERT_STREQ(kNetworkProperties[kShiftBearing], "bearing");
  const Network ex = test::county_exemplar();
  const std::vector<Polygon> region = test::extent_region(ex);
  for (NetworkMethod method : {NetworkMethod::quilt, NetworkMethod::grow})
    for (std::uint64_t seed : {3, 4, 6, 9, 11}) {
      const Network out =
          grow_network(ex, region, nullptr, nullptr, {.seed = seed, .method = method});
      EXPECT_EQ(check_network(out, region, nullptr).total(), 0) << seed;
      const test::PropertyTarget bearing =
          test::property_target(ex, out, region, kShiftBearing, seed);
      EXPECT_LT(bearing.output, bearing.baseline) << seed;
      EXPECT_LE(bearing.output, 0.035) << seed;
      // The quilt's other properties keep the bound (the pass keeps them within a tenth
      // of the exemplar's own variability of where they were; growth's cells are larger than
      // the counties' at seeds 4, 6 and 11 with or without it).
      for (int p = 0; method == NetworkMethod::quilt && p < kShiftBearing; ++p) {
        const test::PropertyTarget other = test::property_target(ex, out, region, p, seed);
        EXPECT_LE(other.output, other.bound) << kNetworkProperties[p] << " at seed " << seed;
      }
    }
}

// A forest's junctions too, after its twigs are pruned: the hand-drawn exemplar's bearings from
// `automatic` (its layout) were 0.191, 0.088, 0.108 at seeds 4, 7 and 10, above the placement
// baseline's 0.098, 0.085, 0.079; the stream trees' 0.021 at seed 6 against 0.019.
TEST(NetworkJunctionShift, ForestBearingsBeatThePlacementBaselineWhereTheyMissedIt) {
  const Network drawn = test::drawn_exemplar();
  for (std::uint64_t seed : {4, 7, 10}) test::expect_target_met(drawn, kShiftBearing, seed);
  test::expect_target_met(test::bench_exemplar("drainage"), kShiftBearing, 6);
}

// The moved lines are committed under the rules of every line: the clearance between lines that
// share no node holds, and the same seed gives the same bytes.
TEST(NetworkJunctionShift, ShiftedCountiesKeepTheClearanceAndTheSameBytes) {
  const Network ex = test::county_exemplar();
  const std::vector<Polygon> region = test::extent_region(ex);
  std::vector<double> lengths;
  for (const NetworkEdge& e : ex.edges) lengths.push_back(polyline_length(e.points));
  std::nth_element(lengths.begin(), lengths.begin() + long(lengths.size() / 2), lengths.end());
  const NetworkGrowthOptions options{
      .seed = 3, .clearance = 0.06 * lengths[lengths.size() / 2], .method = NetworkMethod::quilt};
  const Network a = grow_network(ex, region, nullptr, nullptr, options);
  EXPECT_GE(test::min_distance_between_unrelated(a, options.clearance), options.clearance - 1e-6);
  const Network b = grow_network(ex, region, nullptr, nullptr, options);
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    ASSERT_EQ(a.edges[i].points.size(), b.edges[i].points.size()) << i;
    for (std::size_t k = 0; k < a.edges[i].points.size(); ++k)
      EXPECT_TRUE(a.edges[i].points[k] == b.edges[i].points[k]) << i;
  }
}

}  // namespace
}  // namespace tw
