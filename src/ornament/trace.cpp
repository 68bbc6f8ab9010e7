#include "ornament/trace.hpp"

#include <cmath>
#include <map>

namespace tw {

namespace {

struct Cubic {
  SurfacePoint p[4];
};

// De Casteljau on the surface: every affine combination is a geodesic midpoint. Leaves append
// their control polygons (without the shared first point) to `out`.
bool subdivide(const TerrainSurface& s, const Cubic& c, int depth, std::vector<SurfacePoint>& out) {
  if (depth == 0) {
    out.insert(out.end(), {c.p[1], c.p[2], c.p[3]});
    return true;
  }
  const auto mid = [&](const SurfacePoint& a, const SurfacePoint& b) {
    return s.geodesic_lerp(a, b, 0.5);
  };
  const auto m01 = mid(c.p[0], c.p[1]), m12 = mid(c.p[1], c.p[2]), m23 = mid(c.p[2], c.p[3]);
  if (!m01 || !m12 || !m23) return false;
  const auto m012 = mid(*m01, *m12), m123 = mid(*m12, *m23);
  if (!m012 || !m123) return false;
  const auto m = mid(*m012, *m123);
  if (!m) return false;
  return subdivide(s, {c.p[0], *m01, *m012, *m}, depth - 1, out) &&
         subdivide(s, {*m, *m123, *m23, c.p[3]}, depth - 1, out);
}

}  // namespace

std::optional<TracedElement> trace_element(const TerrainSurface& surface,
                                           const DecorativeElement& element,
                                           const SurfaceFrame& frame, double metres_per_unit,
                                           double rotation, int depth) {
  // One straightest geodesic per distinct control point, so spline ends shared by several
  // splines (and by growth points) map to the very same surface point.
  std::map<std::pair<double, double>, SurfacePoint> mapped;
  const auto map_point = [&](Vec2 q) -> std::optional<SurfacePoint> {
    const auto key = std::pair{q.x, q.y};
    if (const auto it = mapped.find(key); it != mapped.end()) return it->second;
    const auto walk = surface.straightest_geodesic(frame, rotated(q * metres_per_unit, rotation));
    if (!walk) return std::nullopt;
    return mapped.emplace(key, walk->end).first->second;
  };

  TracedElement out;
  for (const BezierSpline& spline : element.splines) {
    SurfaceCurve& curve = out.curves.emplace_back();
    curve.material = spline.material;
    std::vector<SurfacePoint> control;
    for (Vec2 q : spline.control_points) {
      const auto p = map_point(q);
      if (!p) return std::nullopt;
      control.push_back(*p);
    }
    curve.points.push_back(control.front());
    for (std::size_t k = 0; k + 3 < control.size(); k += 3) {
      if (!subdivide(surface, {control[k], control[k + 1], control[k + 2], control[k + 3]}, depth,
                     curve.points)) {
        return std::nullopt;
      }
    }
  }
  for (const GrowthPoint& g : element.growth_points) {
    const auto at = map_point(g.at);
    // The growth direction on the surface: the exponential map's image of a short step along
    // the element's growth direction (its differential, by a finite difference).
    const double step = 0.05;
    const auto ahead = surface.straightest_geodesic(
        frame, rotated((g.at + Vec2{std::cos(g.angle), std::sin(g.angle)} * step) * metres_per_unit,
                       rotation));
    if (!at || !ahead) continue;  // at the window's edge: nothing grows there
    const Vec2 heading = normalized(ahead->end.local - at->local);
    if (length(heading) == 0.0) continue;
    out.growth_points.push_back({g.tag, g.priority, SurfaceFrame{*at, heading}});
  }
  return out;
}

}  // namespace tw
