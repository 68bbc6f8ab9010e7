#include "network/detail/border.hpp"

#include <algorithm>
#include <cmath>

#include "core/segment_distance.hpp"

namespace tw::network_detail {

bool has_drawn_frame(const Network& exemplar, double tolerance, double share) {
  const NodeExtent extent = node_extent(exemplar);
  const Vec2 lo = extent.lo, hi = extent.hi;
  if (!(hi.x > lo.x && hi.y > lo.y)) return false;
  // Only segments reaching within `tolerance` of the perimeter can be near it.
  std::vector<std::pair<Vec2, Vec2>> outer;
  for (const NetworkEdge& e : exemplar.edges)
    for (std::size_t k = 0; k + 1 < e.points.size(); ++k) {
      const Vec2 a = e.points[k], b = e.points[k + 1];
      if (std::min(a.x, b.x) <= lo.x + tolerance || std::max(a.x, b.x) >= hi.x - tolerance ||
          std::min(a.y, b.y) <= lo.y + tolerance || std::max(a.y, b.y) >= hi.y - tolerance)
        outer.push_back({a, b});
    }
  const Vec2 corners[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
  constexpr int kSamples = 64;  // per side
  int near = 0;
  for (int side = 0; side < 4; ++side)
    for (int s = 0; s < kSamples; ++s) {
      const Vec2 p = lerp(corners[side], corners[(side + 1) % 4], (s + 0.5) / kSamples);
      for (const auto& [a, b] : outer)
        if (distance_to_segment(p, a, b) <= tolerance) {
          ++near;
          break;
        }
    }
  return near >= share * 4 * kSamples;
}

}  // namespace tw::network_detail
