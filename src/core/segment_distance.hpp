#pragma once
// The distance from a point to a segment, the one helper for it (strokes, junction rules, leads).
#include <algorithm>

#include "core/vec2.hpp"

namespace tw {

// Distance from p to the segment ab (to a when a == b).
inline double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double length2 = dot(ab, ab);
  const double t = length2 > 0.0 ? std::clamp(dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  return distance(p, a + ab * t);
}

}  // namespace tw
