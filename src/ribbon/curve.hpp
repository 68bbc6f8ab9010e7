#pragma once
// Polyline curves in world metres, parameterized by arc length.
#include <vector>

#include "core/vec2.hpp"

namespace tw {

struct Curve {
  std::vector<Vec2> points;  // for a closed curve the last point is NOT a repeat of the first
  bool closed = false;
};

// Total arc length (including the closing segment of a closed curve).
double arc_length(const Curve& curve);
// Cumulative arc length at each point; one more entry than points for a closed curve
// (the last is the total length back at the first point).
std::vector<double> cumulative_lengths(const Curve& curve);
// The point at arc length x (clamped to [0, L] on open curves, wrapped on closed ones).
Vec2 point_at(const Curve& curve, const std::vector<double>& cumulative, double x);
// Unit tangent at arc length x, from a centred difference over +-h metres.
Vec2 tangent_at(const Curve& curve, const std::vector<double>& cumulative, double x, double h);
// Points every `step` metres along the curve (the last point kept exactly on open curves).
Curve resample(const Curve& curve, double step);
// Removes consecutive duplicate points (closer than `epsilon` metres).
Curve without_duplicates(const Curve& curve, double epsilon = 1e-9);

}  // namespace tw
