#include "network/baseline.hpp"

#include <algorithm>
#include <cmath>

#include "core/split_mix.hpp"
#include "core/warnings.hpp"
#include "network/exemplar.hpp"

namespace tw {

Network baseline_network(const Network& exemplar, const std::vector<Polygon>& region,
                         std::uint64_t seed) {
  SplitMix64 rng(seed);
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (Vec2 p : exemplar.nodes) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  Vec2 rlo{INFINITY, INFINITY}, rhi{-INFINITY, -INFINITY};
  for (const Polygon& polygon : region)
    for (Vec2 p : polygon.front()) {
      rlo = {std::min(rlo.x, p.x), std::min(rlo.y, p.y)};
      rhi = {std::max(rhi.x, p.x), std::max(rhi.y, p.y)};
    }
  const double side = std::max(1e-9, 0.4 * std::min(hi.x - lo.x, hi.y - lo.y));
  const int patches =
      std::max(1, int(std::ceil((rhi.x - rlo.x) * (rhi.y - rlo.y) / (side * side))));
  NetworkLines lines;
  lines.region = region;
  for (int k = 0; k < patches; ++k) {
    const Vec2 from{rng.uniform(lo.x, hi.x - side), rng.uniform(lo.y, hi.y - side)};
    const Vec2 to{rng.uniform(rlo.x - side / 2, rhi.x - side / 2),
                  rng.uniform(rlo.y - side / 2, rhi.y - side / 2)};
    for (const NetworkEdge& e : exemplar.edges) {
      const Vec2 m = e.points[e.points.size() / 2];
      if (m.x < from.x || m.y < from.y || m.x > from.x + side || m.y > from.y + side) continue;
      std::vector<Vec2> moved;
      for (Vec2 p : e.points) moved.push_back(p - from + to);
      lines.lines.push_back(std::move(moved));
      lines.fids.push_back(e.fid);
    }
  }
  // Cut by the region's box (the region is a box in the bench), then noded.
  NetworkLines cut;
  cut.region = region;
  for (std::size_t i = 0; i < lines.lines.size(); ++i) {
    std::vector<Vec2> part;
    const auto flush = [&]() {
      if (part.size() >= 2) cut.lines.push_back(part), cut.fids.push_back(lines.fids[i]);
      part.clear();
    };
    const auto& pts = lines.lines[i];
    const auto in = [&](Vec2 p) {
      return p.x >= rlo.x && p.x <= rhi.x && p.y >= rlo.y && p.y <= rhi.y;
    };
    for (std::size_t k = 0; k < pts.size(); ++k) {
      if (in(pts[k])) {
        if (part.empty() && k > 0) {  // entering: from the boundary
          const Vec2 a = pts[k - 1], b = pts[k];
          double t = 0.0;
          for (double tt : {(rlo.x - a.x) / (b.x - a.x), (rhi.x - a.x) / (b.x - a.x),
                            (rlo.y - a.y) / (b.y - a.y), (rhi.y - a.y) / (b.y - a.y)})
            if (std::isfinite(tt) && tt >= 0 && tt <= 1 && in(lerp(a, b, tt + 1e-12)))
              t = std::max(t, tt);
          part.push_back(lerp(a, b, t));
        }
        part.push_back(pts[k]);
      } else if (!part.empty()) {
        const Vec2 a = pts[k - 1], b = pts[k];
        double t = 1.0;
        for (double tt : {(rlo.x - a.x) / (b.x - a.x), (rhi.x - a.x) / (b.x - a.x),
                          (rlo.y - a.y) / (b.y - a.y), (rhi.y - a.y) / (b.y - a.y)})
          if (std::isfinite(tt) && tt >= 0 && tt <= 1) t = std::min(t, tt);
        part.push_back(lerp(a, b, t));
        flush();
      }
    }
    flush();
  }
  Warnings ignored;
  if (cut.lines.size() < 2) return {};
  return build_planar_network(cut, 0.0, "baseline", ignored);
}

}  // namespace tw
