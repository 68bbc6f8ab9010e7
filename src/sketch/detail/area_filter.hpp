#pragma once
// The world half of area synthesis: candidates mapped into the map, kept inside the polygon,
// off forbidden pixels, and apart from shapes they were disjoint from in the sketch (H3).
#include <functional>
#include <vector>

#include "raster/avoidance.hpp"
#include "raster/polygon.hpp"
#include "sketch/area_synthesis.hpp"
#include "sketch/detail/area_candidates.hpp"

namespace tw::detail {

// `to_world` maps input space into the map; when it is not affine (a curved lead frame),
// `densify` > 0 is the longest segment of input space mapped as a straight one, and shape axes
// are taken over that length.
AreaPattern place_candidates(const SupportHierarchy& h, const std::vector<Candidate>& candidates,
                             const Polygon& domain, const std::function<Vec2(Vec2)>& to_world,
                             double scale, const AvoidanceMap* avoidance, double densify);

}  // namespace tw::detail
