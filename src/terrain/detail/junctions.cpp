#include "terrain/detail/junctions.hpp"

#include <algorithm>
#include <limits>

#include "raster/footprint.hpp"

namespace tw::detail {

namespace {

// Nearest point of a curve to p: (distance, arc length).
std::pair<double, double> nearest_on(const Curve& c, Vec2 p) {
  const auto& pts = c.points;
  const std::size_t count = c.closed ? pts.size() : pts.size() - 1;
  double best = std::numeric_limits<double>::infinity(), best_s = 0.0, s = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec2 a = pts[i], ab = pts[(i + 1) % pts.size()] - a;
    const double len2 = dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    const double d = distance(p, a + ab * t);
    if (d < best) {
      best = d;
      best_s = s + t * std::sqrt(len2);
    }
    s += std::sqrt(len2);
  }
  return {best, best_s};
}

}  // namespace

std::vector<std::vector<EndContact>> find_end_contacts(const std::vector<TerrainFeature>& features,
                                                       double tolerance) {
  std::vector<PieceBox> boxes(features.size());
  std::vector<double> lengths(features.size());
  for (std::size_t i = 0; i < features.size(); ++i) {
    boxes[i] = points_box(features[i].centerline.points);
    lengths[i] = arc_length(features[i].centerline);
  }
  std::vector<std::vector<EndContact>> contacts(features.size());
  for (std::size_t i = 0; i < features.size(); ++i) {
    const auto& f = features[i];
    if (f.centerline.closed) continue;
    for (const bool at_start : {true, false}) {
      const Vec2 end = at_start ? f.centerline.points.front() : f.centerline.points.back();
      for (std::size_t j = 0; j < features.size(); ++j) {
        const auto& g = features[j];
        if (j == i || g.kind != f.kind) continue;
        const double reach = 0.5 * std::max(f.width, g.width) + tolerance;
        if (!meets(grown(boxes[j], reach), PieceBox{end, end})) continue;
        const auto [d, s] = nearest_on(g.centerline, end);
        if (d > reach) continue;
        const bool other_end = !g.centerline.closed && (s <= reach || s >= lengths[j] - reach);
        const double snapped = other_end ? (s <= reach ? 0.0 : lengths[j]) : s;
        contacts[i].push_back({at_start, int(j), snapped, other_end});
      }
    }
  }
  return contacts;
}

}  // namespace tw::detail
