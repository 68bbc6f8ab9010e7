#pragma once
// What the network tests share: an L-shaped field with a pond (a hole) and a forbidden diagonal
// road across it, an exemplar's own extent as a region, and the clearance measure between lines
// that share no node.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/segment_distance.hpp"
#include "network/baseline.hpp"
#include "network/check.hpp"
#include "network/example_networks.hpp"
#include "network/exemplar.hpp"
#include "network/growth.hpp"
#include "network/stats.hpp"
#include "test_support.hpp"

namespace tw::test {

// The road's centreline: x - 0.5 y = 300; cells within 8 m of it are forbidden.
inline double across_diagonal_road(Vec2 p) {
  return p.x - 0.5 * p.y - 300;
}

inline std::vector<Polygon> field_with_pond() {
  return {{{{0, 0}, {900, 0}, {900, 400}, {400, 400}, {400, 800}, {0, 800}},
           {{100, 100}, {250, 100}, {250, 250}, {100, 250}}}};
}

// A network's own extent (the box of its nodes) as a region: an exemplar over its own size, as
// the quality bench measures it.
inline std::vector<Polygon> extent_region(const Network& net) {
  const NodeExtent e = node_extent(net);
  return {{{e.lo, {e.hi.x, e.lo.y}, e.hi, {e.lo.x, e.hi.y}}}};
}

// A synthetic exemplar of `kind` (network/example_networks.hpp, seed 3) `size` metres across, as a
// planar network with its near-junctions snapped within `snap` metres.
inline Network example_exemplar(const std::string& kind, double size, double snap) {
  Warnings w;
  return build_planar_network(example_network(kind, size, 3), snap, kind, w);
}

// The quality bench's exemplar of `kind` (800 m, snapped within 1e-3 m), as
// bench_network_quality builds it.
inline Network bench_exemplar(const std::string& kind) {
  return example_exemplar(kind, 800.0, 1e-3);
}

// The target for one property (an index of network/stats.hpp's properties) of `out`
// against the exemplar `ex` over `region`, as the quality bench measures it: the output's
// distance, the bound it must stay within (1.5 × the exemplar's halves' distance, or 0.05) and
// the placement baseline's distance at `seed`, which it must stay below.
struct PropertyTarget {
  double output = 0.0, bound = 0.0, baseline = 0.0;
};
inline PropertyTarget property_target(const Network& ex, const Network& out,
                                      const std::vector<Polygon>& region, int p,
                                      std::uint64_t seed) {
  const NetworkStats own = network_stats(ex);
  const auto [a, b] = halves(ex);
  const double halves_apart =
      normalized_w1(property(network_stats(ex, a), p), property(network_stats(ex, b), p));
  return {normalized_w1(property(own, p), property(network_stats(out), p)),
          std::max(1.5 * halves_apart, 0.05),
          normalized_w1(property(own, p),
                        property(network_stats(baseline_network(ex, region, seed)), p))};
}

// What `automatic` grows from `ex` over its extent at `seed` has no problem GEOS finds and meets
// the target for property `p`: within the bound and below the placement baseline.
inline void expect_target_met(const Network& ex, int p, std::uint64_t seed) {
  const std::vector<Polygon> region = extent_region(ex);
  const Network out = grow_network(ex, region, nullptr, nullptr, {.seed = seed});
  EXPECT_EQ(check_network(out, region, nullptr).total(), 0) << "seed " << seed;
  const PropertyTarget t = property_target(ex, out, region, p, seed);
  EXPECT_LE(t.output, t.bound) << "seed " << seed;
  EXPECT_LT(t.output, t.baseline) << "seed " << seed;
}

// The county boundaries of North Carolina (r-cran-sf's nc.shp) as a planar network: the real
// exemplar the quality tests share.
inline Network county_exemplar() {
  Warnings w;
  return build_planar_network(
      read_network_lines(
          {.source = (test::source_dir() / "tests/data/nc_counties.geojson").string()}, w),
      1e-3, "exemplar", w);
}

// The hand-drawn exemplar (tests/data/network_drawn.svg: lanes and lines ending a hair short of
// another) as a planar network, as the quality bench builds it.
inline Network drawn_exemplar() {
  Warnings w;
  return build_planar_network(
      read_network_lines({.source = (test::source_dir() / "tests/data/network_drawn.svg").string()},
                         w),
      1e-3, "drawn", w);
}

inline ForbiddenMask diagonal_road_mask() {
  ForbiddenMask forbidden;
  forbidden.grid = {.width = 180,
                    .height = 160,
                    .origin_x = 0,
                    .origin_y = 800,
                    .pixel_width = 5,
                    .pixel_height = 5};
  forbidden.cells = Raster<std::uint8_t>(180, 160, 0);
  for (int r = 0; r < 160; ++r)
    for (int c = 0; c < 180; ++c)
      if (std::abs(across_diagonal_road(forbidden.grid.pixel_centre_world(c, r))) < 8)
        forbidden.cells.at(c, r) = 1;
  return forbidden;
}

// Pairs of edges sharing no node, sampled away from their four end nodes by near_node: the
// smallest distance between them.
inline double min_distance_between_unrelated(const Network& net, double near_node) {
  double best = INFINITY;
  for (std::size_t i = 0; i < net.edges.size(); ++i)
    for (std::size_t j = i + 1; j < net.edges.size(); ++j) {
      const NetworkEdge& a = net.edges[i];
      const NetworkEdge& b = net.edges[j];
      if (a.from == b.from || a.from == b.to || a.to == b.from || a.to == b.to) continue;
      for (std::size_t k = 0; k + 1 < a.points.size(); ++k)
        for (int s = 0; s <= 8; ++s) {
          const Vec2 p = lerp(a.points[k], a.points[k + 1], s / 8.0);
          bool near = false;
          for (int n : {a.from, a.to, b.from, b.to})
            near = near || distance(p, net.nodes[std::size_t(n)]) < near_node;
          if (near) continue;
          for (std::size_t m = 0; m + 1 < b.points.size(); ++m)
            best = std::min(best, distance_to_segment(p, b.points[m], b.points[m + 1]));
        }
    }
  return best;
}

}  // namespace tw::test
