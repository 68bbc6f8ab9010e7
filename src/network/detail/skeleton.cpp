#include "network/detail/skeleton.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace tw::network_detail {

namespace {

double wrap_angle(double a) {  // (-pi, pi]
  constexpr double kPi = std::numbers::pi;
  a = std::fmod(a + kPi, 2 * kPi);
  if (a <= 0) a += 2 * kPi;
  return a - kPi;
}

}  // namespace

double leaving_heading(const std::vector<Vec2>& pts, bool from_start) {
  const std::size_t n = pts.size();
  const Vec2 a = from_start ? pts[0] : pts[n - 1];
  for (std::size_t k = 1; k < n; ++k) {
    const Vec2 b = from_start ? pts[k] : pts[n - 1 - k];
    if (!(b == a)) return std::atan2(b.y - a.y, b.x - a.x);
  }
  return 0.0;
}

std::vector<double> long_stroke_edges(const Network& ex, double deflection, double min_fraction,
                                      double min_share) {
  const std::size_t ne = ex.edges.size();
  // Per node, the edges leaving it (edge index, which end) with their headings.
  struct Leaving {
    int edge;
    int end;  // 0: the edge starts here
    double heading;
  };
  std::vector<std::vector<Leaving>> at(ex.nodes.size());
  for (std::size_t i = 0; i < ne; ++i) {
    const NetworkEdge& e = ex.edges[i];
    if (e.from == e.to) continue;  // a closed loop is a stroke by itself
    at[std::size_t(e.from)].push_back({int(i), 0, leaving_heading(e.points, true)});
    at[std::size_t(e.to)].push_back({int(i), 1, leaving_heading(e.points, false)});
  }
  // The edge continuing edge `i` (arriving at its end `end`) least deflected, or -1.
  const auto best_continuation = [&](int node, int edge, int end) {
    const NetworkEdge& e = ex.edges[std::size_t(edge)];
    const double arrive = leaving_heading(e.points, end == 0) + std::numbers::pi;
    int best = -1;
    double best_deflection = deflection;
    for (const Leaving& l : at[std::size_t(node)]) {
      if (l.edge == edge) continue;
      const double d = std::abs(wrap_angle(l.heading - arrive));
      if (d < best_deflection) best_deflection = d, best = l.edge;
    }
    return best;
  };
  // Mutual best continuations pair edges at a node; strokes are the chains of such pairs.
  std::vector<std::array<int, 2>> next(ne, {-1, -1});
  for (std::size_t n = 0; n < ex.nodes.size(); ++n)
    for (const Leaving& l : at[n]) {
      const int other = best_continuation(int(n), l.edge, l.end);
      if (other < 0) continue;
      const NetworkEdge& o = ex.edges[std::size_t(other)];
      const int other_end = o.from == int(n) ? 0 : 1;
      if (best_continuation(int(n), other, other_end) == l.edge)
        next[std::size_t(l.edge)][l.end] = other;
    }
  const NodeExtent extent = node_extent(ex);
  const Vec2 lo = extent.lo, hi = extent.hi;
  const double min_length = min_fraction * std::max(hi.x - lo.x, hi.y - lo.y);
  std::vector<int> stroke(ne, -1);
  std::vector<double> stroke_length;
  for (std::size_t i = 0; i < ne; ++i) {
    if (stroke[i] >= 0) continue;
    const int id = int(stroke_length.size());
    double length = 0.0;
    std::vector<int> todo{int(i)};
    while (!todo.empty()) {
      const int e = todo.back();
      todo.pop_back();
      if (stroke[std::size_t(e)] >= 0) continue;
      stroke[std::size_t(e)] = id;
      length += polyline_length(ex.edges[std::size_t(e)].points);
      for (int k = 0; k < 2; ++k)
        if (next[std::size_t(e)][std::size_t(k)] >= 0)
          todo.push_back(next[std::size_t(e)][std::size_t(k)]);
    }
    stroke_length.push_back(length);
  }
  std::vector<double> is_long(ne, 0.0);
  double long_length = 0.0;
  for (std::size_t i = 0; i < ne; ++i)
    if (stroke_length[std::size_t(stroke[i])] >= min_length) {
      is_long[i] = stroke_length[std::size_t(stroke[i])];
      long_length += polyline_length(ex.edges[i].points);
    }
  if (long_length < min_share * ex.total_length()) std::fill(is_long.begin(), is_long.end(), 0.0);
  return is_long;
}

}  // namespace tw::network_detail
