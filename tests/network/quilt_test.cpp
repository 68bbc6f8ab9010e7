// Graph quilting (docs/networks.md, "Quilting"): the rules every network keeps (no crossing
// but at nodes, inside a region with a hole, off forbidden cells, the clearance, same seed same
// bytes), and the exemplar's style per property on an exemplar quilting suits: the crocodile
// cells (Y-junctions, cells of one size), where growth misses the angles and the areas.
#include <gtest/gtest.h>

#include <cmath>

#include "core/segment_distance.hpp"
#include "network/baseline.hpp"
#include "network/check.hpp"
#include "network/example_networks.hpp"
#include "network/exemplar.hpp"
#include "network/growth.hpp"
#include "network/stats.hpp"
#include "network_fixtures.hpp"

namespace tw {
namespace {

std::vector<Polygon> square(double side) {
  return {{{{0, 0}, {side, 0}, {side, side}, {0, side}}}};
}

TEST(NetworkQuilt, KeepsTheRulesInAPolygonWithAHoleAndIsDeterministic) {
  const Network ex = test::example_exemplar("bocage", 600.0, 1.0);
  const std::vector<Polygon> region = test::field_with_pond();
  const ForbiddenMask forbidden = test::diagonal_road_mask();
  NetworkGrowthOptions options;
  options.seed = 4;
  options.clearance = 6.0;
  options.method = NetworkMethod::quilt;
  NetworkGrowthReport report;
  const Network out = grow_network(ex, region, &forbidden, nullptr, options, &report);
  EXPECT_GT(out.edges.size(), 60u);
  EXPECT_GT(report.placed, 60);
  const NetworkCheck check = check_network(out, region, &forbidden);
  EXPECT_EQ(check.crossings, 0) << check.first;
  EXPECT_EQ(check.outside, 0) << check.first;
  EXPECT_EQ(check.forbidden, 0) << check.first;
  // Unrelated lines (sharing no node) keep the clearance away from the nodes.
  EXPECT_GE(test::min_distance_between_unrelated(out, options.clearance), options.clearance - 1e-6);
  const Network again = grow_network(ex, region, &forbidden, nullptr, options);
  ASSERT_EQ(again.edges.size(), out.edges.size());
  for (std::size_t i = 0; i < out.edges.size(); ++i)
    ASSERT_EQ(again.edges[i].points, out.edges[i].points);
}

// `automatic` makes both and keeps the closer to the exemplar's style: on the crocodile cells
// that is the quilt (growth makes T-junctions where the exemplar has Y-junctions), the same bytes
// as asked for by name; completing a partial network is growth.
TEST(NetworkQuilt, AutomaticKeepsTheQuiltWhereItIsCloser) {
  const Network ex = test::example_exemplar("crocodile", 400.0, 1.0);
  const auto region = square(400.0);
  NetworkGrowthReport report;
  const Network automatic = grow_network(ex, region, nullptr, nullptr, {.seed = 1}, &report);
  EXPECT_TRUE(report.quilted);
  EXPECT_EQ(chosen_network_method(report), "quilt");
  const Network quilt =
      grow_network(ex, region, nullptr, nullptr, {.seed = 1, .method = NetworkMethod::quilt});
  ASSERT_EQ(automatic.edges.size(), quilt.edges.size());
  for (std::size_t i = 0; i < quilt.edges.size(); ++i)
    ASSERT_EQ(automatic.edges[i].points, quilt.edges[i].points);
  Network partial;
  partial.nodes = {{50.0, 200.0}, {350.0, 200.0}};
  partial.edges = {{.from = 0, .to = 1, .points = {{50.0, 200.0}, {350.0, 200.0}}, .kept = true}};
  NetworkGrowthReport completed;
  grow_network(ex, region, nullptr, &partial, {.seed = 1}, &completed);
  EXPECT_FALSE(completed.quilted);
  EXPECT_EQ(chosen_network_method(completed), "growth");
  EXPECT_GT(completed.stubs, 0);  // grown from the drawn ends
}

// One test per style property: the crocodile exemplar (400 m) quilted over a square of its
// size, seeds 1 and 2: each property's distance to the exemplar is below a bound measured with
// margin and below the naive placement baseline's (docs/networks.md, "Quality"); degrees are
// closer than the tiling baseline's, and the dangling ends stay at the exemplar's rate (none).
class QuiltProperty : public ::testing::TestWithParam<int> {};

TEST_P(QuiltProperty, CrocodileCellsKeepTheExemplarsStyle) {
  static const Network ex = test::example_exemplar("crocodile", 400.0, 1.0);
  static const auto region = square(400.0);
  // The networks of both seeds, made once for the six properties.
  struct Made {
    NetworkStats quilt, placed, tiled;
    std::int64_t problems = 0;
  };
  static const std::vector<Made> made = [] {
    std::vector<Made> all;
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      NetworkGrowthOptions options;
      options.seed = seed;
      options.method = NetworkMethod::quilt;
      const Network out = grow_network(ex, region, nullptr, nullptr, options);
      all.push_back({network_stats(out), network_stats(baseline_network(ex, region, seed)),
                     network_stats(baseline_network(ex, region, seed, BaselineKind::tiling)),
                     check_network(out, region, nullptr).total()});
    }
    return all;
  }();
  const NetworkStats se = network_stats(ex);
  const int p = GetParam();
  for (std::size_t k = 0; k < made.size(); ++k) {
    const Made& m = made[k];
    EXPECT_EQ(m.problems, 0);
    const double d_out = normalized_w1(property(se, p), property(m.quilt, p));
    const double d_placed = normalized_w1(property(se, p), property(m.placed, p));
    const double d_tiled = normalized_w1(property(se, p), property(m.tiled, p));
    // Bounds: about twice the largest measured on 2026-12-03 over both seeds (degree 0.000,
    // edge length 0.237, curvature 0.222, junction angle 0.094, face area 0.267, bearing 0.102).
    constexpr double kBound[] = {0.05, 0.5, 0.4, 0.25, 0.8, 0.2};
    EXPECT_LT(d_out, kBound[p]) << kNetworkProperties[p] << " seed " << k + 1;
    // Closer than the random placement of exemplar squares, but for bearings: the placement
    // copies the exemplar unturned, so its bearings are the exemplar's (quilting is as close for
    // one seed, 0.102 to 0.097, and closer for the other).
    if (p != 5) {
      EXPECT_LT(d_out, d_placed) << kNetworkProperties[p] << " seed " << k + 1;
    }
    if (p == 0) {
      EXPECT_LT(d_out, d_tiled) << "seed " << k + 1;  // the tiling breaks degrees at its seams
      EXPECT_LE(m.quilt.dangling_per_km(), 1.5 * se.dangling_per_km() + 0.5) << "seed " << k + 1;
    }
  }
}

// The county boundaries of North Carolina quilted over their bounding box, seeds 1 to 3: the
// edges' curvature, the faces' areas and the edges' lengths stay within 1.5 × the exemplar's
// half-to-half distance and below the naive placement baseline's. Before the blocks were chosen
// for real (the empty-square test refused every candidate but the last) and slivers between
// seams were left out, seed 2's faces (1.29 against 0.96) and seed 3's curvature (2.39 against
// 0.20: a tiny ring stitched from two slivers) missed.
TEST(NetworkQuilt, CountiesKeepTheirCurvatureAndFaceAreas) {
  const Network ex = test::county_exemplar();
  const std::vector<Polygon> region = test::extent_region(ex);
  const NetworkStats se = network_stats(ex);
  const auto [half_a, half_b] = halves(ex);
  const NetworkStats s1 = network_stats(ex, half_a), s2 = network_stats(ex, half_b);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const Network out =
        grow_network(ex, region, nullptr, nullptr, {.seed = seed, .method = NetworkMethod::quilt});
    EXPECT_EQ(check_network(out, region, nullptr).total(), 0) << "seed " << seed;
    const NetworkStats so = network_stats(out);
    const NetworkStats sb = network_stats(baseline_network(ex, region, seed));
    for (int p : {1, 2, 4}) {  // edge length, curvature, face area
      const double d_out = normalized_w1(property(se, p), property(so, p));
      EXPECT_LE(d_out, 1.5 * normalized_w1(property(s1, p), property(s2, p)))
          << kNetworkProperties[p] << " seed " << seed;
      EXPECT_LT(d_out, normalized_w1(property(se, p), property(sb, p)))
          << kNetworkProperties[p] << " seed " << seed;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Properties, QuiltProperty, ::testing::Range(0, 6), [](const auto& info) {
  return std::string(kNetworkProperties[info.param]);
});

}  // namespace
}  // namespace tw
