// Growth from the exemplar's layout (docs/networks.md, "Layout"): where the exemplar's style is
// global (rings and spokes around one centre, terrace walls across the whole slope), `automatic`
// lays out its long strokes first and grows the rest from their junctions, and comes closer to
// the exemplar than growth alone on the properties that structure decides.
#include <gtest/gtest.h>

#include <cmath>

#include "network/baseline.hpp"
#include "network/check.hpp"
#include "network/example_networks.hpp"
#include "network/exemplar.hpp"
#include "network/growth.hpp"
#include "network/stats.hpp"
#include "network_fixtures.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

// The layout's exemplars: 400 m across.
Network layout_exemplar(const std::string& kind) {
  return test::example_exemplar(kind, 400.0, 1e-3);
}

std::vector<Polygon> layout_region(const Network& ex) {
  return test::extent_region(ex);
}

double layout_distance(const Network& ex, const Network& out, int p) {
  return normalized_w1(property(network_stats(ex), p), property(network_stats(out), p));
}

constexpr int kDegree = 0, kEdgeLength = 1, kCurvature = 2, kJunctionAngle = 3, kFaceArea = 4,
              kBearing = 5;

// `automatic` over a region of the exemplar's size, seed 1: it chose the layout, and the
// output keeps every rule.
struct LaidOut {
  Network ex;
  std::vector<Polygon> region;
  Network out;
};
LaidOut laid_out(const std::string& kind) {
  LaidOut l{layout_exemplar(kind), {}, {}};
  l.region = layout_region(l.ex);
  NetworkGrowthReport report;
  l.out = grow_network(l.ex, l.region, nullptr, nullptr, {.seed = 1}, &report);
  EXPECT_TRUE(report.laid_out) << kind;
  EXPECT_EQ(chosen_network_method(report), "layout") << kind;
  EXPECT_EQ(check_network(l.out, l.region, nullptr).total(), 0) << kind;
  return l;
}

TEST(NetworkLayout, RadialKeepsItsJunctionAnglesAndCellsAroundOneCentre) {
  const auto [ex, region, out] = laid_out("radial");
  const Network grown =
      grow_network(ex, region, nullptr, nullptr, {.seed = 1, .method = NetworkMethod::grow});
  const double angle = layout_distance(ex, out, kJunctionAngle);
  const double cells = layout_distance(ex, out, kFaceArea);
  EXPECT_LT(angle, 0.5 * layout_distance(ex, grown, kJunctionAngle)) << angle;
  EXPECT_LT(cells, 0.5 * layout_distance(ex, grown, kFaceArea)) << cells;
  // Same seed, same bytes.
  const Network again = grow_network(ex, region, nullptr, nullptr, {.seed = 1});
  ASSERT_EQ(again.edges.size(), out.edges.size());
  for (std::size_t i = 0; i < out.edges.size(); ++i)
    ASSERT_EQ(again.edges[i].points, out.edges[i].points);
}

// The exemplar's spokes end a hair past the outer ring and start a hair short of the first: its
// dangling ends are copied (moved to keep the clearance) rather than dropped, which left
// T-junctions the exemplar does not have; and its empty corners beyond the outer ring are
// copied too, not seeded with growth. Degrees and junction angles within 1.5 x the halves at
// three seeds (main: 8 x and 7 x beyond).
TEST(NetworkLayout, RadialKeepsItsDanglingSpokeEndsAndEmptyCorners) {
  const Network ex = layout_exemplar("radial");
  const std::vector<Polygon> region = layout_region(ex);
  const auto [a, b] = halves(ex);
  const NodeExtent extent = node_extent(ex);
  const Vec2 lo = extent.lo, hi = extent.hi;
  const Vec2 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * (hi.x - lo.x);
  for (std::uint64_t seed : {1, 2, 3}) {
    NetworkGrowthReport report;
    const Network out = grow_network(ex, region, nullptr, nullptr, {.seed = seed}, &report);
    EXPECT_EQ(chosen_network_method(report), "layout") << seed;
    EXPECT_EQ(check_network(out, region, nullptr).total(), 0) << seed;
    for (int p : {kDegree, kJunctionAngle}) {
      const double own =
          normalized_w1(property(network_stats(ex, a), p), property(network_stats(ex, b), p));
      EXPECT_LE(layout_distance(ex, out, p), std::max(1.5 * own, 0.05))
          << kNetworkProperties[p] << " seed " << seed;
    }
    int in_corners = 0;  // vertices well beyond the outer ring, towards the region's corners
    for (const NetworkEdge& e : out.edges)
      for (Vec2 p : e.points)
        in_corners +=
            std::abs(p.x - centre.x) > 0.8 * radius && std::abs(p.y - centre.y) > 0.8 * radius;
    EXPECT_EQ(in_corners, 0) << seed;
  }
}

// Turned by a lead bearing, the radial exemplar's copies turn each about its own centre (its
// corners are empty: the copies are islands), so no neighbouring copy's ring reaches into the
// region's corners (on a grid turned with the copies, those at 30° did).
TEST(NetworkLayout, RadialTurnedByALeadBearingKeepsItsCornersEmpty) {
  const Network ex = layout_exemplar("radial");
  const std::vector<Polygon> region = layout_region(ex);
  const NodeExtent extent = node_extent(ex);
  const Vec2 lo = extent.lo, hi = extent.hi;
  const Vec2 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * (hi.x - lo.x);
  NetworkGrowthOptions options;
  options.seed = 1;
  options.method = NetworkMethod::layout;
  options.lead_bearing = 30.0;
  NetworkGrowthReport report;
  const Network out = grow_network(ex, region, nullptr, nullptr, options, &report);
  EXPECT_TRUE(report.laid_out);
  EXPECT_EQ(check_network(out, region, nullptr).total(), 0);
  int in_corners = 0;
  for (const NetworkEdge& e : out.edges)
    for (Vec2 p : e.points)
      in_corners +=
          std::abs(p.x - centre.x) > 0.8 * radius && std::abs(p.y - centre.y) > 0.8 * radius;
  EXPECT_EQ(in_corners, 0);
  EXPECT_GT(out.edges.size(), ex.edges.size() / 2);
}

TEST(NetworkLayout, TerraceWallsKeepTheirDegreesAndCells) {
  const auto [ex, region, out] = laid_out("terraces");
  const auto [a, b] = halves(ex);
  for (int p : {kDegree, kFaceArea}) {
    const double own =
        normalized_w1(property(network_stats(ex, a), p), property(network_stats(ex, b), p));
    EXPECT_LE(layout_distance(ex, out, p), std::max(1.5 * own, 0.05)) << kNetworkProperties[p];
  }
}

// Issue #20's target for one property at one seed: within 1.5 x the exemplar's half-to-half
// distance (or 0.05) and closer than the naive placement baseline.
void expect_layout_target(const Network& ex, const Network& out, const Network& base, int p,
                          std::uint64_t seed) {
  const auto [a, b] = halves(ex);
  const double own =
      normalized_w1(property(network_stats(ex, a), p), property(network_stats(ex, b), p));
  const double d = layout_distance(ex, out, p);
  EXPECT_LE(d, std::max(1.5 * own, 0.05)) << kNetworkProperties[p] << " seed " << seed;
  EXPECT_LT(d, layout_distance(ex, base, p)) << kNetworkProperties[p] << " seed " << seed;
}

// The terrace walls' ramps are straight in the exemplar: each laid-out junction takes its own
// ramp (kept at the exemplar's spacing from the wall beside it, where growth's clearance test
// refused it and a drawn, snapped and bent candidate came instead), and a wall grazing the
// region's edge leaves no sliver (a sharply bent edge 11 m long). Curvature beats the placement
// baseline at seeds 1-3 (before: 0.50 and 0.35 against 0.09 and 0.12 at seeds 1 and 2).
TEST(NetworkLayout, TerraceRampsStayStraightAndCurvatureBeatsTheBaseline) {
  const Network ex = layout_exemplar("terraces");
  const std::vector<Polygon> region = layout_region(ex);
  for (std::uint64_t seed : {1, 2, 3}) {
    NetworkGrowthReport report;
    const Network out = grow_network(ex, region, nullptr, nullptr, {.seed = seed}, &report);
    EXPECT_EQ(chosen_network_method(report), "layout") << seed;
    EXPECT_EQ(check_network(out, region, nullptr).total(), 0) << seed;
    expect_layout_target(ex, out, baseline_network(ex, region, seed), kCurvature, seed);
  }
}

// The hand-drawn exemplar (tests/data/network_drawn.svg) has lines ending a hair short of
// another (near T-junctions, dangling ends in its statistics): a long stroke that almost meets
// a longer one gives way to it (its end moved back), the laid-out lines keep the exemplar's
// spacing where they meet, and a copied junction's own piece keeps its dangling end instead of
// snapping onto a line. Degrees, edge lengths and bearings meet the target at seeds
// 1-3 (before: bearings at no seed, degrees not at seed 3, edge lengths not at seeds 1 and 3).
TEST(NetworkLayout, DrawnNearTJunctionsKeepTheirDegreesAndBearings) {
  const Network ex = test::drawn_exemplar();
  const std::vector<Polygon> region = layout_region(ex);
  for (std::uint64_t seed : {1, 2, 3}) {
    NetworkGrowthReport report;
    const Network out = grow_network(ex, region, nullptr, nullptr, {.seed = seed}, &report);
    EXPECT_EQ(chosen_network_method(report), "layout") << seed;
    EXPECT_EQ(check_network(out, region, nullptr).total(), 0) << seed;
    const Network base = baseline_network(ex, region, seed);
    for (int p : {kDegree, kEdgeLength, kBearing}) expect_layout_target(ex, out, base, p, seed);
  }
}

// `layout` asked for by name (`--method layout`, `network.method: layout`) is the candidate
// `automatic` keeps on the terraces, byte for byte, not growth's network, and the same bytes
// twice; on an exemplar without long strokes (the crocodile cells) it is growth, byte for byte.
TEST(NetworkLayout, AskedByNameItIsTheCandidateAutomaticKeeps) {
  const auto same_bytes = [](const Network& a, const Network& b) {
    if (a.nodes != b.nodes || a.edges.size() != b.edges.size()) return false;
    for (std::size_t i = 0; i < a.edges.size(); ++i)
      if (a.edges[i].points != b.edges[i].points) return false;
    return true;
  };
  const auto [ex, region, automatic] = laid_out("terraces");
  const NetworkGrowthOptions layout{.seed = 1, .method = NetworkMethod::layout};
  NetworkGrowthReport report;
  const Network named = grow_network(ex, region, nullptr, nullptr, layout, &report);
  EXPECT_TRUE(report.laid_out);
  EXPECT_FALSE(report.quilted);
  EXPECT_TRUE(same_bytes(named, automatic));
  EXPECT_TRUE(same_bytes(named, grow_network(ex, region, nullptr, nullptr, layout)));
  const Network grown =
      grow_network(ex, region, nullptr, nullptr, {.seed = 1, .method = NetworkMethod::grow});
  EXPECT_FALSE(same_bytes(named, grown));
  EXPECT_LT(layout_distance(ex, named, kFaceArea), layout_distance(ex, grown, kFaceArea));

  const Network cells = layout_exemplar("crocodile");
  const auto cells_region = layout_region(cells);
  NetworkGrowthReport cells_report;
  const Network cells_named =
      grow_network(cells, cells_region, nullptr, nullptr, layout, &cells_report);
  EXPECT_FALSE(cells_report.laid_out);
  EXPECT_EQ(chosen_network_method(cells_report), "growth");  // growth, byte for byte
  EXPECT_TRUE(same_bytes(cells_named, grow_network(cells, cells_region, nullptr, nullptr,
                                                   {.seed = 1, .method = NetworkMethod::grow})));
}

}  // namespace
}  // namespace tw
