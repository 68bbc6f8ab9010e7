#include "network/detail/forest.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>

#include "core/boost_geometry.hpp"
#include "network/detail/skeleton.hpp"

namespace tw::network_detail {

double empty_space_quantile(const Network& exemplar, double spacing, double quantile) {
  using namespace geometry;
  using EmptySpaceSegment = std::pair<BgSegment, int>;
  std::vector<EmptySpaceSegment> segments;
  for (const NetworkEdge& e : exemplar.edges)
    for (std::size_t k = 0; k + 1 < e.points.size(); ++k)
      segments.push_back({BgSegment(to_bg(e.points[k]), to_bg(e.points[k + 1])), 0});
  if (segments.empty() || !(spacing > 0.0)) return 0.0;
  const bgi::rtree<EmptySpaceSegment, bgi::quadratic<16>> tree(segments.begin(), segments.end());
  Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2 hi = -1.0 * lo;
  for (Vec2 p : exemplar.nodes) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  // At most about 10⁶ points, whatever the exemplar's extent in edge lengths.
  const double step = std::max(spacing, std::sqrt((hi.x - lo.x) * (hi.y - lo.y) / 1e6));
  const int nx = std::max(1, int(std::ceil((hi.x - lo.x) / step)));
  const int ny = std::max(1, int(std::ceil((hi.y - lo.y) / step)));
  std::vector<double> distances;
  distances.reserve(std::size_t(nx) * std::size_t(ny));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const BgPoint p(lo.x + (i + 0.5) * (hi.x - lo.x) / nx, lo.y + (j + 0.5) * (hi.y - lo.y) / ny);
      std::vector<EmptySpaceSegment> nearest;
      tree.query(bgi::nearest(p, 1), std::back_inserter(nearest));
      distances.push_back(bg::distance(nearest.front().first, p));
    }
  const std::size_t at = std::min(
      distances.size() - 1, std::size_t(std::clamp(quantile, 0.0, 1.0) * double(distances.size())));
  std::nth_element(distances.begin(), distances.begin() + long(at), distances.end());
  return distances[at];
}

JunctionsGoingOn junctions_going_on(const Network& exemplar, double deflection) {
  constexpr double kPi = std::numbers::pi;
  std::vector<std::vector<double>> headings(exemplar.nodes.size());
  for (const NetworkEdge& e : exemplar.edges) {
    headings[std::size_t(e.from)].push_back(leaving_heading(e.points, true));
    headings[std::size_t(e.to)].push_back(leaving_heading(e.points, false));
  }
  JunctionsGoingOn count;
  for (std::size_t n = 0; n < headings.size(); ++n) {
    const std::vector<double>& h = headings[n];
    if ((!exemplar.on_boundary.empty() && exemplar.on_boundary[n]) ||
        (h.size() != 3 && h.size() != 4))
      continue;
    // Edges with another edge leaving opposite them (the same line going on through the node).
    int going_on = 0;
    for (std::size_t a = 0; a < h.size(); ++a)
      for (std::size_t b = 0; b < h.size(); ++b) {
        const double opposite = std::remainder(h[a] - h[b] - kPi, 2 * kPi);
        if (a != b && std::abs(opposite) < deflection) {
          ++going_on;
          break;
        }
      }
    if (h.size() == 3) ++count.three_way;
    if (h.size() == 4 && going_on == 4) ++count.crossings;
    if (h.size() == 3 && going_on >= 2) ++count.t_junctions;
  }
  return count;
}

bool lines_cross_more_than_they_end_on_lines(const Network& exemplar, double deflection) {
  const JunctionsGoingOn count = junctions_going_on(exemplar, deflection);
  return count.crossings > count.t_junctions;
}

}  // namespace tw::network_detail
