#include "pipeline/detail/area_lead.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/segment_distance.hpp"
#include "raster/rasterize.hpp"

namespace tw::detail {

namespace {

bool segments_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

double segment_distance(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  if (segments_cross(a, b, c, d)) return 0.0;
  return std::min({distance_to_segment(a, c, d), distance_to_segment(b, c, d),
                   distance_to_segment(c, a, b), distance_to_segment(d, a, b)});
}

double folded_angle(Vec2 v) {
  double a = std::atan2(v.y, v.x);
  if (a < 0.0) a += std::numbers::pi;
  return a >= std::numbers::pi ? a - std::numbers::pi : a;
}

}  // namespace

std::optional<double> nearest_line_angle(const Polygon& polygon,
                                         const std::vector<const LineFeature*>& lines) {
  const Ring& ring = polygon.front();
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (Vec2 p : ring)
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)},
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  // Segments by the distance of their box to the ring's box (a lower bound), then exactly.
  struct Candidate {
    double bound;
    Vec2 a, b;
  };
  std::vector<Candidate> candidates;
  for (const LineFeature* line : lines) {
    const auto& pts = line->points;
    if (pts.size() < 2) continue;
    const std::size_t n = line->closed ? pts.size() : pts.size() - 1;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 a = pts[i], b = pts[(i + 1) % pts.size()];
      const double dx = std::max({0.0, lo.x - std::max(a.x, b.x), std::min(a.x, b.x) - hi.x});
      const double dy = std::max({0.0, lo.y - std::max(a.y, b.y), std::min(a.y, b.y) - hi.y});
      candidates.push_back({std::hypot(dx, dy), a, b});
    }
  }
  if (candidates.empty()) return std::nullopt;
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& x, const Candidate& y) { return x.bound < y.bound; });
  double best = INFINITY;
  Vec2 direction{1.0, 0.0};
  for (const Candidate& c : candidates) {
    if (c.bound > best) break;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const double d = segment_distance(ring[i], ring[(i + 1) % ring.size()], c.a, c.b);
      if (d < best) best = d, direction = c.b - c.a;
    }
  }
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

}  // namespace tw::detail
