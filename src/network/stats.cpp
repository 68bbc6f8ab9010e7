#include "network/stats.hpp"

#include <ogr_geometry.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

namespace tw {

namespace {

bool inside(std::optional<StatsWindow> w, Vec2 p) {
  return !w || (p.x >= w->lo.x && p.x <= w->hi.x && p.y >= w->lo.y && p.y <= w->hi.y);
}

// Heading (radians) leaving `node` along the edge's first distinct segment from that end.
double leaving(const NetworkEdge& e, bool from_start) {
  const std::size_t n = e.points.size();
  const Vec2 a = from_start ? e.points[0] : e.points[n - 1];
  for (std::size_t k = 1; k < n; ++k) {
    const Vec2 b = from_start ? e.points[k] : e.points[n - 1 - k];
    if (!(b == a)) return std::atan2(b.y - a.y, b.x - a.x);
  }
  return 0.0;
}

}  // namespace

NetworkStats network_stats(const Network& net, std::optional<StatsWindow> window) {
  NetworkStats s;
  const std::vector<int> degree = net.degrees();
  std::vector<std::vector<double>> headings(net.nodes.size());
  for (const NetworkEdge& e : net.edges) {
    headings[std::size_t(e.from)].push_back(leaving(e, true));
    headings[std::size_t(e.to)].push_back(leaving(e, false));
  }
  const auto on_boundary = [&](int n) {
    return !net.on_boundary.empty() && net.on_boundary[std::size_t(n)];
  };
  for (std::size_t n = 0; n < net.nodes.size(); ++n) {
    if (degree[n] == 0 || on_boundary(int(n)) || !inside(window, net.nodes[n])) continue;
    s.degree.push_back(degree[n]);
    if (degree[n] == 1) ++s.dangling;
    if (degree[n] >= 3) {
      std::vector<double> h = headings[n];
      std::sort(h.begin(), h.end());
      for (std::size_t k = 0; k < h.size(); ++k) {
        double gap = (k + 1 < h.size() ? h[k + 1] : h[0] + 2 * std::numbers::pi) - h[k];
        s.junction_angle.push_back(gap * 180.0 / std::numbers::pi);
      }
    }
  }
  for (const NetworkEdge& e : net.edges) {
    const Vec2 mid = 0.5 * (e.points.front() + e.points.back());
    const double length = polyline_length(e.points);
    if (!inside(window, e.points[e.points.size() / 2]) && !inside(window, mid)) continue;
    s.length_m += length;
    if (!on_boundary(e.from) && !on_boundary(e.to)) s.edge_length.push_back(length);
    if (length > 0.0) s.curvature.push_back(polyline_turning(e.points) / length);
    const Vec2 chord = e.points.back() - e.points.front();
    if (length > 0.0 && !(chord == Vec2{})) {
      double bearing = std::atan2(chord.x, chord.y) * 180.0 / std::numbers::pi;  // from north
      bearing = std::fmod(bearing + 360.0, 180.0);
      s.bearing.push_back(bearing);
    }
  }
  OGRMultiLineString all;
  for (const NetworkEdge& e : net.edges) {
    OGRLineString ls;
    for (Vec2 p : e.points) ls.addPoint(p.x, p.y);
    all.addGeometry(&ls);
  }
  std::unique_ptr<OGRGeometry> faces(all.Polygonize());
  if (faces) {
    for (const OGRGeometry* g : *faces->toGeometryCollection()) {
      if (wkbFlatten(g->getGeometryType()) != wkbPolygon) continue;
      OGRPoint c;
      if (window && g->Centroid(&c) == OGRERR_NONE && !inside(window, {c.getX(), c.getY()}))
        continue;
      s.face_area.push_back(g->toPolygon()->get_Area());
    }
  }
  return s;
}

double normalized_w1(std::vector<double> a, std::vector<double> b) {
  if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  // Integral of |F_a - F_b| over the merged support.
  std::size_t i = 0, j = 0;
  double w = 0.0, previous = std::min(a[0], b[0]);
  while (i < a.size() || j < b.size()) {
    const double x = j >= b.size() || (i < a.size() && a[i] <= b[j]) ? a[i] : b[j];
    w += std::abs(double(i) / a.size() - double(j) / b.size()) * (x - previous);
    previous = x;
    while (i < a.size() && a[i] == x) ++i;
    while (j < b.size() && b[j] == x) ++j;
  }
  double mean = 0.0, var = 0.0;
  for (double v : a) mean += v;
  mean /= a.size();
  for (double v : a) var += (v - mean) * (v - mean);
  const double spread = std::sqrt(var / a.size());
  return w / (spread > 0.0 ? spread : 1.0);
}

const std::vector<double>& property(const NetworkStats& s, int index) {
  switch (index) {
    case 0:
      return s.degree;
    case 1:
      return s.edge_length;
    case 2:
      return s.curvature;
    case 3:
      return s.junction_angle;
    case 4:
      return s.face_area;
    default:
      return s.bearing;
  }
}

std::pair<StatsWindow, StatsWindow> halves(const Network& net) {
  const NodeExtent extent = node_extent(net);
  const Vec2 lo = extent.lo, hi = extent.hi;
  const bool along_x = hi.x - lo.x >= hi.y - lo.y;
  std::vector<double> v;
  for (Vec2 p : net.nodes) v.push_back(along_x ? p.x : p.y);
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  const double cut = v[v.size() / 2];
  StatsWindow a{lo, hi}, b{lo, hi};
  if (along_x)
    a.hi.x = cut, b.lo.x = std::nextafter(cut, INFINITY);
  else
    a.hi.y = cut, b.lo.y = std::nextafter(cut, INFINITY);
  return {a, b};
}

}  // namespace tw
