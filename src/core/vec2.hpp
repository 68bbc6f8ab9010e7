#pragma once
// A 2-D vector of doubles: world coordinates in metres (x east, y north) or pixel coordinates.
#include <cmath>

namespace tw {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;

  friend constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
  friend constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
  friend constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
  friend constexpr Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
  friend constexpr Vec2 operator*(double s, Vec2 a) { return {a.x * s, a.y * s}; }
  friend constexpr Vec2 operator/(Vec2 a, double s) { return {a.x / s, a.y / s}; }
  friend constexpr bool operator==(Vec2 a, Vec2 b) = default;
  constexpr Vec2& operator+=(Vec2 b) { x += b.x; y += b.y; return *this; }
  constexpr Vec2& operator-=(Vec2 b) { x -= b.x; y -= b.y; return *this; }
};

constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
// z component of the 3-D cross product: > 0 when b is counter-clockwise of a.
constexpr double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double length(Vec2 a) { return std::hypot(a.x, a.y); }
inline double distance(Vec2 a, Vec2 b) { return length(b - a); }
// Rotated by +90 degrees (counter-clockwise in a y-up frame): the left normal of a tangent.
constexpr Vec2 perp(Vec2 a) { return {-a.y, a.x}; }
// Turned by `radians` counter-clockwise (in a y-up frame) about the origin.
inline Vec2 rotated(Vec2 v, double radians) {
  const double c = std::cos(radians), s = std::sin(radians);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}
inline Vec2 normalized(Vec2 a) {
  const double n = length(a);
  return n > 0.0 ? a / n : Vec2{};
}
constexpr Vec2 lerp(Vec2 a, Vec2 b, double t) { return a + (b - a) * t; }
inline bool is_finite(Vec2 a) { return std::isfinite(a.x) && std::isfinite(a.y); }

}  // namespace tw
