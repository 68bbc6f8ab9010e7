#include "pipeline/lead_direction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/boost_geometry.hpp"
#include "raster/rasterize.hpp"
#include "sketch/area_synthesis.hpp"

namespace tw {

namespace {

using namespace geometry;

double folded_angle(Vec2 v) {
  double a = std::atan2(v.y, v.x);
  if (a < 0.0) a += std::numbers::pi;
  return a >= std::numbers::pi ? a - std::numbers::pi : a;
}

}  // namespace

double compass_degrees(double radians) {
  const double d = std::fmod(90.0 - radians * 180.0 / std::numbers::pi, 360.0);
  // fmod keeps the sign, and a tiny negative d + 360 rounds to 360 itself: fold both into [0, 360).
  const double folded = d < 0.0 ? d + 360.0 : d;
  return folded >= 360.0 ? 0.0 : folded;
}

double angle_from_compass(double degrees) {
  return (90.0 - degrees) * std::numbers::pi / 180.0;
}

std::optional<double> nearest_line_angle(const Polygon& polygon,
                                         const std::vector<const LineFeature*>& lines) {
  const Ring& ring = polygon.front();
  std::vector<BgSegment> edges;
  BgBox ring_box = bg::make_inverse<BgBox>();
  for (std::size_t i = 0; i < ring.size(); ++i) {
    edges.emplace_back(to_bg(ring[i]), to_bg(ring[(i + 1) % ring.size()]));
    bg::expand(ring_box, to_bg(ring[i]));
  }
  // The lines' segments by their boxes, in reading order (ties keep it).
  std::vector<BgSegment> segments;
  std::vector<std::pair<BgBox, std::size_t>> boxes;
  for (const LineFeature* line : lines) {
    const auto& pts = line->points;
    if (pts.size() < 2) continue;
    const std::size_t n = line->closed ? pts.size() : pts.size() - 1;
    for (std::size_t i = 0; i < n; ++i) {
      segments.emplace_back(to_bg(pts[i]), to_bg(pts[(i + 1) % pts.size()]));
      boxes.emplace_back(bg::return_envelope<BgBox>(segments.back()), segments.size() - 1);
    }
  }
  if (segments.empty()) return std::nullopt;
  const bgi::rtree<std::pair<BgBox, std::size_t>, bgi::rstar<16>> index(boxes);
  // Segments nearest first by the distance of their box to the ring's box (a lower bound on
  // their distance to the ring), then exactly (Boost.Geometry's segment distance: 0 where they
  // intersect), until the bound passes the best distance found. Segments of equal bound go in
  // reading order, so the first of equally near segments wins whatever the tree's order.
  double best = INFINITY;
  Vec2 direction{1.0, 0.0};
  std::vector<std::size_t> group;
  double group_bound = -1.0;
  const auto measure = [&] {
    std::sort(group.begin(), group.end());
    for (const std::size_t s : group)
      for (const BgSegment& edge : edges) {
        const double d = bg::distance(edge, segments[s]);
        if (d < best) {
          best = d;
          direction = Vec2{segments[s].second.x() - segments[s].first.x(),
                           segments[s].second.y() - segments[s].first.y()};
        }
      }
    group.clear();
  };
  for (auto it = index.qbegin(bgi::nearest(ring_box, unsigned(boxes.size()))); it != index.qend();
       ++it) {
    const double bound = bg::distance(ring_box, it->first);
    if (bound != group_bound) {
      measure();
      if (bound > best) break;
      group_bound = bound;
    }
    group.push_back(it->second);
  }
  measure();
  return folded_angle(direction);
}

std::optional<double> contour_angle(const Polygon& polygon, HeightSampler& heights) {
  const Ring& ring = polygon.front();
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (Vec2 p : ring)
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)},
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  constexpr int kSamples = 32;
  GridSpec lattice;
  lattice.width = lattice.height = kSamples;
  lattice.origin_x = lo.x, lattice.origin_y = hi.y;
  lattice.pixel_width = std::max(1e-9, (hi.x - lo.x) / kSamples);
  lattice.pixel_height = std::max(1e-9, (hi.y - lo.y) / kSamples);
  Raster<std::uint8_t> inside;
  burn_polygons({polygon}, lattice, Window::whole(lattice), inside, 1);
  const double step = 0.5 * std::min(heights.grid().pixel_width, heights.grid().pixel_height);
  double xx = 0.0, xy = 0.0, yy = 0.0, magnitude = 0.0;
  int count = 0;
  for (int row = 0; row < kSamples; ++row)
    for (int col = 0; col < kSamples; ++col) {
      if (!inside.at(col, row)) continue;
      const Vec2 p = lattice.pixel_centre_world(col, row);
      const double gx =
          (heights.bilinear({p.x + step, p.y}) - heights.bilinear({p.x - step, p.y})) / (2 * step);
      const double gy =
          (heights.bilinear({p.x, p.y + step}) - heights.bilinear({p.x, p.y - step})) / (2 * step);
      if (!std::isfinite(gx) || !std::isfinite(gy)) continue;
      xx += gx * gx, xy += gx * gy, yy += gy * gy;
      magnitude += std::hypot(gx, gy);
      ++count;
    }
  if (count == 0 || magnitude / count < 1e-3) return std::nullopt;
  // The structure tensor's principal axis is the dominant gradient (sign-free, so opposite
  // slopes of a valley agree); contours run across it.
  const double gradient = 0.5 * std::atan2(2.0 * xy, xx - yy);
  return folded_angle({-std::sin(gradient), std::cos(gradient)});
}

std::vector<const LineFeature*> road_lines(const std::vector<FeatureClassConfig>& classes,
                                           const std::vector<std::vector<LineFeature>>& lines) {
  std::vector<const LineFeature*> roads;
  for (std::size_t c = 0; c < classes.size() && c < lines.size(); ++c)
    if (classes[c].kind == FeatureKind::road)
      for (const LineFeature& line : lines[c]) roads.push_back(&line);
  return roads;
}

const Polygon& lead_polygon(const std::vector<Polygon>& region) {
  if (region.empty()) throw std::logic_error("lead_polygon: an empty region");
  return *std::max_element(region.begin(), region.end(), [](const Polygon& a, const Polygon& b) {
    return polygon_area(a) < polygon_area(b);
  });
}

LeadAngle lead_angle(Lead lead, double bearing_deg, const Polygon& polygon,
                     const std::vector<const LineFeature*>& roads, HeightSampler& heights) {
  std::optional<double> angle;
  switch (lead) {
    case Lead::bearing:
      return {angle_from_compass(bearing_deg), false};
    case Lead::long_axis:
      return {long_axis_bearing(polygon), false};
    case Lead::nearest_road:
      angle = nearest_line_angle(polygon, roads);
      break;
    case Lead::contours:
      angle = contour_angle(polygon, heights);
      break;
  }
  if (angle) return {*angle, false};
  return {long_axis_bearing(polygon), true};
}

}  // namespace tw
