// Whole cells at the border (docs/networks.md, "Finish"): an exemplar of closed cells whose
// border is its outermost cells' own sides (no frame drawn around it, no cut line, no dead end)
// gets the same border: the output's lines cut by the region's boundary are taken out to their
// junctions, and its outermost cells stay whole.
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

constexpr int kCellsEdgeLength = 1, kCellsCurvature = 2;

std::vector<Polygon> whole_cells_region(const Network& ex) {
  return test::extent_region(ex);
}

// The bench's crocodile cells (docs/networks.md, "Quality"), seed 3: before, the quilt's lines
// ran on to the region's boundary, and the exemplar's long, bent border edges (its outermost
// hexagons' sides merged through their corners) had no counterpart: edge lengths at 0.145 and
// curvature at 0.160 against halves of 0.026 and 0.011.
TEST(NetworkWholeCells, CrocodileCellsBorderIsTheirOwnSides) {
  const Network ex = test::bench_exemplar("crocodile");
  const std::vector<Polygon> region = whole_cells_region(ex);
  const Network out = grow_network(ex, region, nullptr, nullptr, {.seed = 3});
  EXPECT_EQ(check_network(out, region, nullptr).total(), 0);
  // No line is left ending on the boundary: every end is a junction of closed cells.
  const std::vector<int> degree = out.degrees();
  for (std::size_t n = 0; n < out.nodes.size(); ++n) {
    EXPECT_FALSE(out.on_boundary[n]) << n;
    EXPECT_GE(degree[n], 3) << n;
  }
  const NetworkStats se = network_stats(ex), so = network_stats(out),
                     sb = network_stats(baseline_network(ex, region, 3));
  const auto [a, b] = halves(ex);
  const NetworkStats s1 = network_stats(ex, a), s2 = network_stats(ex, b);
  for (int p : {kCellsEdgeLength, kCellsCurvature}) {
    const double d_out = normalized_w1(property(se, p), property(so, p));
    EXPECT_LE(d_out, std::max(1.5 * normalized_w1(property(s1, p), property(s2, p)), 0.05))
        << kNetworkProperties[p];
    EXPECT_LT(d_out, normalized_w1(property(se, p), property(sb, p))) << kNetworkProperties[p];
  }
}

// A frame drawn around the exemplar (the bocage's outer hedge along its whole extent) is its
// border: the lines reaching the region's boundary are kept, cut there.
TEST(NetworkWholeCells, AFramedExemplarKeepsItsLinesCutByTheRegion) {
  Warnings w;
  const Network ex = build_planar_network(example_network("bocage", 400.0, 3), 1e-3, "bocage", w);
  const Network out = grow_network(ex, whole_cells_region(ex), nullptr, nullptr,
                                   {.seed = 1, .method = NetworkMethod::grow});
  int cut = 0;
  for (char b : out.on_boundary) cut += b != 0;
  EXPECT_GT(cut, 4);
}

}  // namespace
}  // namespace tw
