#include "network/network.hpp"

#include <algorithm>
#include <cmath>

namespace tw {

std::vector<int> Network::degrees() const {
  std::vector<int> degree(nodes.size(), 0);
  for (const NetworkEdge& e : edges) {
    ++degree[std::size_t(e.from)];
    ++degree[std::size_t(e.to)];
  }
  return degree;
}

double polyline_length(const std::vector<Vec2>& points) {
  double sum = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) sum += distance(points[i - 1], points[i]);
  return sum;
}

double polyline_turning(const std::vector<Vec2>& points) {
  double turning = 0.0;
  for (std::size_t k = 1; k + 1 < points.size(); ++k) {
    const Vec2 a = points[k] - points[k - 1], b = points[k + 1] - points[k];
    turning += std::abs(std::atan2(cross(a, b), dot(a, b)));
  }
  return turning;
}

NodeExtent node_extent(const Network& network) {
  NodeExtent e{{INFINITY, INFINITY}, {-INFINITY, -INFINITY}};
  for (Vec2 p : network.nodes) {
    e.lo = {std::min(e.lo.x, p.x), std::min(e.lo.y, p.y)};
    e.hi = {std::max(e.hi.x, p.x), std::max(e.hi.y, p.y)};
  }
  return e;
}

double Network::total_length() const {
  double sum = 0.0;
  for (const NetworkEdge& e : edges) sum += polyline_length(e.points);
  return sum;
}

}  // namespace tw
