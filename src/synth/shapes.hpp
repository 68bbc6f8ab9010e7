#pragma once
// Built-in curves for the CLI, tests and pictures (world metres, origin at (0, 0)).
#include <string>

#include "ribbon/curve.hpp"

namespace tw {

// "line" (length L), "arc" (half circle of radius L/2), "s-curve" (two opposite half circles
// of radius L/4), "circle" (radius L/2, closed), "heart" (closed, about L wide), "hairpin" (two
// parallel legs L long, 0.12 L apart, joined by a half circle: folds ribbons wider than 0.12 L).
// L = length_scale > 0; unknown names throw tw::Error listing the known ones.
Curve make_shape(const std::string& name, double length_scale);

}  // namespace tw
