#pragma once
// The style of a network as distributions (docs/networks.md, "Quality"): node degrees, edge
// lengths, curvature along edges, angles between consecutive edges at junctions, cell (face)
// areas and edge bearings, and the rate of dangling ends; compared by a normalized
// Wasserstein-1 distance.
#include <optional>
#include <vector>

#include "network/network.hpp"

namespace tw {

struct NetworkStats {
  std::vector<double> degree;          // per node not on the region's boundary
  std::vector<double> edge_length;     // metres, per edge not ending on the boundary
  std::vector<double> curvature;       // per edge: total absolute turning (rad) per metre
  std::vector<double> junction_angle;  // degrees between consecutive edges at nodes of degree >= 3
  std::vector<double> face_area;       // m², per closed cell (GEOS polygonize)
  std::vector<double> bearing;         // degrees [0, 180) of each edge's chord, from north
  double length_m = 0.0;
  int dangling = 0;  // nodes of degree 1 not on the boundary
  double dangling_per_km() const { return length_m > 0.0 ? dangling / (length_m / 1000.0) : 0.0; }
};

// Only what lies in the box [lo, hi] when given (nodes by position, edges and faces by their
// middle), with degrees from the whole graph: the halves of an exemplar.
struct StatsWindow {
  Vec2 lo, hi;
};
NetworkStats network_stats(const Network& network, std::optional<StatsWindow> window = {});

// Wasserstein-1 between two samples divided by the spread (standard deviation) of `reference`
// (1 when it has none); infinity when either sample is empty.
double normalized_w1(std::vector<double> reference, std::vector<double> other);

// The property names in the order of the comparison table, and their samples.
inline constexpr const char* kNetworkProperties[] = {"degree",         "edge_length", "curvature",
                                                     "junction_angle", "face_area",   "bearing"};
const std::vector<double>& property(const NetworkStats& stats, int index);

// The exemplar's two halves (split across its longer side at the median node).
std::pair<StatsWindow, StatsWindow> halves(const Network& network);

}  // namespace tw
