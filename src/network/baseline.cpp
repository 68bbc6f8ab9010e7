#include "network/baseline.hpp"

#include <algorithm>
#include <cmath>

#include "core/split_mix.hpp"
#include "core/warnings.hpp"
#include "network/detail/box_clip.hpp"
#include "network/exemplar.hpp"

namespace tw {

using network_detail::cut_to_box;

Network baseline_network(const Network& exemplar, const std::vector<Polygon>& region,
                         std::uint64_t seed, BaselineKind kind) {
  SplitMix64 rng(seed);
  const NodeExtent extent = node_extent(exemplar);
  const Vec2 lo = extent.lo, hi = extent.hi;
  Vec2 rlo{INFINITY, INFINITY}, rhi{-INFINITY, -INFINITY};
  for (const Polygon& polygon : region)
    for (Vec2 p : polygon.front()) {
      rlo = {std::min(rlo.x, p.x), std::min(rlo.y, p.y)};
      rhi = {std::max(rhi.x, p.x), std::max(rhi.y, p.y)};
    }
  const double side = std::max(1e-9, 0.4 * std::min(hi.x - lo.x, hi.y - lo.y));
  NetworkLines lines;
  lines.region = region;
  std::vector<std::vector<Vec2>> parts;
  if (kind == BaselineKind::placement) {
    // Squares of the exemplar dropped at random places, as many as cover the region once on
    // average (overlapping in places, leaving gaps in others), then cut by the region's box.
    const int patches =
        std::max(1, int(std::ceil((rhi.x - rlo.x) * (rhi.y - rlo.y) / (side * side))));
    for (int k = 0; k < patches; ++k) {
      const Vec2 from{rng.uniform(lo.x, hi.x - side), rng.uniform(lo.y, hi.y - side)};
      const Vec2 to{rng.uniform(rlo.x - side / 2, rhi.x - side / 2),
                    rng.uniform(rlo.y - side / 2, rhi.y - side / 2)};
      for (const NetworkEdge& e : exemplar.edges) {
        parts.clear();
        cut_to_box(e.points, from, from + Vec2{side, side}, parts);
        for (auto& part : parts) {
          std::vector<Vec2> moved;
          for (Vec2 p : part) moved.push_back(p - from + to);
          std::vector<std::vector<Vec2>> inside;
          cut_to_box(moved, rlo, rhi, inside);
          for (auto& piece : inside) {
            lines.lines.push_back(std::move(piece));
            lines.fids.push_back(e.fid);
          }
        }
      }
    }
  }
  // Tiling: the region tiled by squares, each filled with an exemplar square from a random
  // place: no matching across the seams.
  for (double y = rlo.y; kind == BaselineKind::tiling && y < rhi.y; y += side)
    for (double x = rlo.x; x < rhi.x; x += side) {
      const Vec2 from{rng.uniform(lo.x, hi.x - side), rng.uniform(lo.y, hi.y - side)};
      const Vec2 to{x, y};
      const Vec2 cell_hi{std::min(x + side, rhi.x), std::min(y + side, rhi.y)};
      for (const NetworkEdge& e : exemplar.edges) {
        parts.clear();
        cut_to_box(e.points, from, from + (cell_hi - to), parts);
        for (auto& part : parts) {
          for (Vec2& p : part) p = p - from + to;
          lines.lines.push_back(std::move(part));
          lines.fids.push_back(e.fid);
        }
      }
    }
  Warnings ignored;
  if (lines.lines.size() < 2) return {};
  return build_planar_network(lines, 0.0, "baseline", ignored);
}

}  // namespace tw
