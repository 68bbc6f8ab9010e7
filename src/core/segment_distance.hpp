#pragma once
// The distance from a point to a segment, the one helper for it (strokes, junction rules, leads),
// and a segment's part outside a disc or prolonged to it (the clearance around a junction).
#include <algorithm>
#include <cmath>

#include "core/vec2.hpp"

namespace tw {

// Distance from p to the segment ab (to a when a == b).
inline double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double length2 = dot(ab, ab);
  const double t = length2 > 0.0 ? std::clamp(dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  return distance(p, a + ab * t);
}

// Trims ab to its part outside the disc (j, r); false when nothing is left. A disc wholly
// beyond either end leaves ab as it is; one over its middle keeps the longer side.
inline bool trim_outside_disc(Vec2& a, Vec2& b, Vec2 j, double r) {
  const Vec2 d = b - a, f = a - j;
  const double A = dot(d, d), B = 2.0 * dot(f, d), C = dot(f, f) - r * r;
  if (A <= 0.0) return C >= 0.0;
  const double disc = B * B - 4.0 * A * C;
  if (disc <= 0.0) return true;
  // The line through ab is inside the disc for t1 < t < t2 (a at t = 0, b at t = 1).
  const double t1 = (-B - std::sqrt(disc)) / (2.0 * A), t2 = (-B + std::sqrt(disc)) / (2.0 * A);
  if (t2 <= 0.0 || t1 >= 1.0) return true;
  if (t1 <= 0.0 && t2 >= 1.0) return false;
  const Vec2 p1 = a + d * t1, p2 = a + d * t2;
  if (t1 <= 0.0) return a = p2, true;
  if (t2 >= 1.0) return b = p1, true;
  if (t1 > 1.0 - t2)
    b = p1;
  else
    a = p2;
  return true;
}

// Extends ab along its line to the near side of the disc (j, r) when the disc lies wholly beyond
// one of its ends, at most `reach` beyond it; unchanged otherwise.
inline void prolong_to_disc(Vec2& a, Vec2& b, Vec2 j, double r, double reach) {
  const Vec2 d = b - a, f = a - j;
  const double A = dot(d, d), B = 2.0 * dot(f, d), C = dot(f, f) - r * r;
  if (A <= 0.0) return;
  const double disc = B * B - 4.0 * A * C;
  if (disc <= 0.0) return;
  const double t1 = (-B - std::sqrt(disc)) / (2.0 * A), t2 = (-B + std::sqrt(disc)) / (2.0 * A);
  const double length = std::sqrt(A);
  if (t1 >= 1.0 && (t1 - 1.0) * length <= reach) b = a + d * t1;
  if (t2 <= 0.0 && -t2 * length <= reach) a = a + d * t2;
}

}  // namespace tw
