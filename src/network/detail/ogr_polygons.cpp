#include "network/detail/ogr_polygons.hpp"

namespace tw::detail {

OGRMultiPolygon to_ogr(const std::vector<Polygon>& polygons) {
  OGRMultiPolygon mp;
  for (const Polygon& polygon : polygons) {
    OGRPolygon p;
    for (const Ring& ring : polygon) {
      OGRLinearRing r;
      for (Vec2 v : ring) r.addPoint(v.x, v.y);
      r.closeRings();
      p.addRing(&r);
    }
    mp.addGeometry(&p);
  }
  return mp;
}

}  // namespace tw::detail
