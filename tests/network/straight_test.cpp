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
  const Network ex = test::bench_exemplar("grid");
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

// The distance of property `p` between the exemplar and `out`, with its target (1.5 x the
// exemplar's halves, or 0.05) and the placement baseline's distance at `seed`.
struct JogDistances {
  double out = 0.0, target = 0.0, baseline = 0.0;
};
JogDistances jog_distances(const Network& ex, const Network& out,
                           const std::vector<Polygon>& region, std::uint64_t seed, int p) {
  const auto [a, b] = halves(ex);
  const NetworkStats se = network_stats(ex);
  return {normalized_w1(property(se, p), property(network_stats(out), p)),
          std::max(1.5 * normalized_w1(property(network_stats(ex, a), p),
                                       property(network_stats(ex, b), p)),
                   0.05),
          normalized_w1(property(se, p),
                        property(network_stats(baseline_network(ex, region, seed)), p))};
}

// The bench's grid laid out (its long tracks copied), seeds 1 and 3: before, an edge ending on
// a junction by a step of 3 m (or 4 m) then turning 90° (a field boundary laid a few metres
// beside the junction it ends at) was a corner over 17 m, curvature 0.09 /m where the
// exemplar's largest is 0.009 (its frame's corners): curvature distances 0.83 and 0.29 against
// a target of 0.204 and a baseline of 0.155. Such jogs left out: 0.134 and 0.053; `automatic`
// keeps the layout at seed 1, whose bearings are the grid's (0.023; growth's 0.155 before).
TEST(NetworkStraight, GridEdgesLoseTheJogsBesideTheirJunctions) {
  const Network ex = test::bench_exemplar("grid");
  const std::vector<Polygon> region = straight_region(ex);
  for (std::uint64_t seed : {1, 3}) {
    const Network out =
        grow_network(ex, region, nullptr, nullptr, {.seed = seed, .method = NetworkMethod::layout});
    EXPECT_EQ(check_network(out, region, nullptr).total(), 0) << seed;
    const JogDistances d = jog_distances(ex, out, region, seed, kStraightCurvature);
    EXPECT_LE(d.out, d.target) << seed;
    EXPECT_LT(d.out, d.baseline) << seed;
  }
  constexpr int kBearing = 5;
  const Network chosen = grow_network(ex, region, nullptr, nullptr, {.seed = 1});
  const JogDistances d = jog_distances(ex, chosen, region, 1, kBearing);
  EXPECT_LE(d.out, d.target);
  EXPECT_LT(d.out, d.baseline);
}

// The bench's bocage (fields split by straight hedges), seed 1: before, a 4 m edge whose last
// hair of a step turned 90° (a snapped end) and corners at nodes of degree 2 that neither their
// chord nor their removal could undo gave a curvature distance of 1.71 (its placement baseline:
// 0.116); hairs left out and such corners made T-junctions farther on, 0.23.
TEST(NetworkStraight, BocageHedgesLoseTheirHairStepsAndCorners) {
  const Network ex = test::bench_exemplar("bocage");
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

// Corners inside one edge (a copied frame corner) and corners whose continuation ends at a node
// of degree 2 (Growth 8): before, neither was continued as a T, and the bocage's curvature
// distance at seed 1 was 0.214 (0.130 with the grid's jogs and the forest's twigs merged),
// above the baseline's 0.116; now 0.097. (Its seeds 2 and 3 move with `automatic`'s choice,
// 0.15-0.55 with or without the change: seed 1 is the one that tells.) The grid's at seed 3
// stays within its target (halves 0.136: 0.204).
TEST(NetworkStraight, CornersInsideEdgesAndFacingNodesBecomeTs) {
  const Network bocage = test::bench_exemplar("bocage");
  const std::vector<Polygon> region = straight_region(bocage);
  const auto curvature_distance = [](const Network& ex, const Network& out) {
    return normalized_w1(property(network_stats(ex), kStraightCurvature),
                         property(network_stats(out), kStraightCurvature));
  };
  for (std::uint64_t seed : {1, 2, 3}) {
    const Network out = grow_network(bocage, region, nullptr, nullptr, {.seed = seed});
    EXPECT_EQ(check_network(out, region, nullptr).total(), 0) << seed;
    if (seed == 1) {
      EXPECT_LT(curvature_distance(bocage, out),
                curvature_distance(bocage, baseline_network(bocage, region, seed)));
    }
  }
  const Network grid = test::bench_exemplar("grid");
  const std::vector<Polygon> grid_region = straight_region(grid);
  const Network out = grow_network(grid, grid_region, nullptr, nullptr, {.seed = 3});
  EXPECT_EQ(check_network(out, grid_region, nullptr).total(), 0);
  const auto [a, b] = halves(grid);
  const double d_halves = normalized_w1(property(network_stats(grid, a), kStraightCurvature),
                                        property(network_stats(grid, b), kStraightCurvature));
  EXPECT_LE(curvature_distance(grid, out), std::max(1.5 * d_halves, 0.05));
}

// The bocage's corners left at seed 3 (Growth 8): two faced a junction within the clearance,
// which a corner was never joined onto, and one was a straight line with a hair step at its end
// left by a later link. Before, its curvature distance was 0.545 there, far above the
// baseline's 0.116; now 0.089. The junctions of four made cost its degrees little (0.011).
TEST(NetworkStraight, BocageCornersFacingAJunctionJoinItAndLoseTheirHairs) {
  const Network bocage = test::bench_exemplar("bocage");
  const std::vector<Polygon> region = straight_region(bocage);
  const Network out = grow_network(bocage, region, nullptr, nullptr, {.seed = 3});
  EXPECT_EQ(check_network(out, region, nullptr).total(), 0);
  const NetworkStats ex = network_stats(bocage), got = network_stats(out);
  const double d_base = normalized_w1(
      property(ex, kStraightCurvature),
      property(network_stats(baseline_network(bocage, region, 3)), kStraightCurvature));
  EXPECT_LT(normalized_w1(property(ex, kStraightCurvature), property(got, kStraightCurvature)),
            d_base);
  EXPECT_LE(normalized_w1(ex.degree, got.degree), 0.05);
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
