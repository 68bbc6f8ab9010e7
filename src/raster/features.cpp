#include "raster/features.hpp"

#include <cmath>

#include "core/error.hpp"

namespace tw {

std::vector<Polygon> to_polygons(const std::vector<PolygonFeature>& features) {
  std::vector<Polygon> polygons;
  polygons.reserve(features.size());
  for (const PolygonFeature& f : features) {
    if (f.rings.empty()) fail("{}: polygon FID {} has no ring", f.source, f.fid);
    for (std::size_t r = 0; r < f.rings.size(); ++r) {
      if (f.rings[r].size() < 3)
        fail("{}: polygon FID {} ring {} has {} points (need 3)", f.source, f.fid, r,
             f.rings[r].size());
      for (const Vec2 p : f.rings[r])
        if (!is_finite(p))
          fail("{}: polygon FID {} ring {} has a non-finite point", f.source, f.fid, r);
    }
    polygons.push_back(f.rings);
  }
  return polygons;
}

void add_features(const std::vector<PolygonFeature>& polygons,
                  const std::vector<LineFeature>& lines, AvoidanceInputs& inputs) {
  for (Polygon& p : to_polygons(polygons)) inputs.polygons.push_back(std::move(p));
  for (const LineFeature& f : lines) {
    if (!(f.width >= 0.0) || !std::isfinite(f.width))
      fail("{}: line FID {} has width {} m (need >= 0)", f.source, f.fid, f.width);
    for (const Vec2 p : f.points)
      if (!is_finite(p)) fail("{}: line FID {} has a non-finite point", f.source, f.fid);
    std::vector<Vec2> points = f.points;
    if (f.closed && points.size() > 2) points.push_back(points.front());
    inputs.lines.push_back(std::move(points));
    inputs.line_widths.push_back(f.width);
  }
}

}  // namespace tw
