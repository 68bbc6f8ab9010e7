#include "network/network.hpp"

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

double Network::total_length() const {
  double sum = 0.0;
  for (const NetworkEdge& e : edges) sum += polyline_length(e.points);
  return sum;
}

}  // namespace tw
