#include "pipeline/detail/polygons_hash.hpp"

namespace tw::detail {

void hash_polygons_meeting(Hasher& h, const std::vector<Polygon>& polygons, const PieceBox& box) {
  for (const Polygon& polygon : polygons) {
    if (polygon.empty() || !meets(points_box(polygon.front()), box)) continue;
    h.u64(polygon.size());
    for (const Ring& ring : polygon) h.points(ring);
  }
}

}  // namespace tw::detail
