#pragma once
// A curve network as a planar graph (docs/networks.md): nodes where lines meet or end, edges as
// whole polylines between them. Exemplars, partial networks drawn by the user and synthesized
// networks are all this one value type.
#include <cstdint>
#include <vector>

#include "core/vec2.hpp"

namespace tw {

struct NetworkEdge {
  int from = 0, to = 0;      // node indices; points.front() is nodes[from], back() nodes[to]
  std::vector<Vec2> points;  // metres, at least two
  bool kept = false;         // drawn by the user (autocomplete): written exactly as read
  std::int64_t fid = -1;     // the source feature, when read
};

struct Network {
  std::vector<Vec2> nodes;
  std::vector<NetworkEdge> edges;
  // Per node: it lies on the region's boundary (a line cut there, not a dangling end).
  std::vector<char> on_boundary;

  std::vector<int> degrees() const;
  double total_length() const;
};

// The box [lo, hi] of a network's nodes (an exemplar's extent; lo > hi when it has none).
struct NodeExtent {
  Vec2 lo, hi;
};
NodeExtent node_extent(const Network& network);

double polyline_length(const std::vector<Vec2>& points);
// Total absolute turning (radians) at the interior vertices: 0 for a straight line.
double polyline_turning(const std::vector<Vec2>& points);

}  // namespace tw
