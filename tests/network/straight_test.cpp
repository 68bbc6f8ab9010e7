// Straight edges (docs/networks.md, "Finish"): where the exemplar's edges are nearly all
// straight, the output's edges are made straight where their chords keep every rule, and bent
// (corners) only as often as the exemplar's are, so that their curvature comes as close to the
// exemplar's as its own halves are to each other.
#include <gtest/gtest.h>

#include <cmath>

#include "network/baseline.hpp"
#include "network/check.hpp"
#include "network/example_networks.hpp"
#include "network/exemplar.hpp"
#include "network/growth.hpp"
#include "network/stats.hpp"
#include "network_fixtures.hpp"

namespace tw {
namespace {

constexpr int kStraightCurvature = 2;

std::vector<Polygon> straight_region(const Network& ex) {
  return test::extent_region(ex);
}

double bent_share(const Network& net) {
  std::size_t bent = 0;
  for (const NetworkEdge& e : net.edges) bent += polyline_turning(e.points) >= 0.01;
  return double(bent) / double(net.edges.size());
}

// The bench's grid (docs/networks.md, "Quality"), seed 1: before, six merged corners of 137
// edges where the exemplar has four of 157 (its frame's), a curvature distance of 0.29 against
// halves of 0.14 and a baseline of 0.155.
TEST(NetworkStraight, AStraightExemplarsCurvatureIsMetOnTheGrid) {
  Warnings w;
  const Network ex = build_planar_network(example_network("grid", 800.0, 3), 1e-3, "grid", w);
  const std::vector<Polygon> region = straight_region(ex);
  const Network out = grow_network(ex, region, nullptr, nullptr, {.seed = 1});
  EXPECT_EQ(check_network(out, region, nullptr).total(), 0);
  EXPECT_LE(bent_share(out), bent_share(ex) + 1.0 / double(out.edges.size()));
  const auto [a, b] = halves(ex);
  const double d_halves = normalized_w1(property(network_stats(ex, a), kStraightCurvature),
                                        property(network_stats(ex, b), kStraightCurvature));
  const double d_base =
      normalized_w1(property(network_stats(ex), kStraightCurvature),
                    property(network_stats(baseline_network(ex, region, 1)), kStraightCurvature));
  const double d_out = normalized_w1(property(network_stats(ex), kStraightCurvature),
                                     property(network_stats(out), kStraightCurvature));
  EXPECT_LE(d_out, std::max(1.5 * d_halves, 0.05));
  EXPECT_LT(d_out, d_base);
}

// The bench's bocage (fields split by straight hedges), seed 1: before, a 4 m edge whose last
// hair of a step turned 90° (a snapped end) and corners at nodes of degree 2 that neither their
// chord nor their removal could undo gave a curvature distance of 1.71 (its placement baseline:
// 0.116); hairs left out and such corners made T-junctions farther on, 0.23.
TEST(NetworkStraight, BocageHedgesLoseTheirHairStepsAndCorners) {
  Warnings w;
  const Network ex = build_planar_network(example_network("bocage", 800.0, 3), 1e-3, "bocage", w);
  const std::vector<Polygon> region = straight_region(ex);
  const Network out = grow_network(ex, region, nullptr, nullptr, {.seed = 1});
  EXPECT_EQ(check_network(out, region, nullptr).total(), 0);
  const double d_out = normalized_w1(property(network_stats(ex), kStraightCurvature),
                                     property(network_stats(out), kStraightCurvature));
  EXPECT_LT(d_out, 0.5);
  const double d_base =
      normalized_w1(property(network_stats(ex), kStraightCurvature),
                    property(network_stats(baseline_network(ex, region, 1)), kStraightCurvature));
  EXPECT_LT(d_out, 2.0 * d_base);
}

// A curved exemplar (terrace walls along contours) keeps its bends: nothing is straightened.
TEST(NetworkStraight, ACurvedExemplarKeepsItsBends) {
  Warnings w;
  const Network ex =
      build_planar_network(example_network("terraces", 400.0, 3), 1e-3, "terraces", w);
  const Network out = grow_network(ex, straight_region(ex), nullptr, nullptr,
                                   {.seed = 1, .method = NetworkMethod::grow});
  EXPECT_GT(bent_share(out), 0.25);
}

}  // namespace
}  // namespace tw
