#pragma once
// Clustering and statistics for the sketch analysis: mean shift (flat kernel, nanoflann radius
// search), axial (orientation) statistics, and PCA boxes (Eigen).
#include <vector>

#include "core/vec2.hpp"
#include "sketch/hierarchy.hpp"

namespace tw::detail {

// Mean shift with a flat kernel of radius `bandwidth` over 1-D values: the label of each value's
// mode, labels numbered by first appearance (deterministic).
std::vector<int> mean_shift_1d(const std::vector<double>& values, double bandwidth);

// The same over orientations in [0, pi) (axial: 0 and pi are one orientation).
std::vector<int> mean_shift_axial(const std::vector<double>& angles, double bandwidth);

// Axial mean in [0, pi) and circular standard deviation (radians) of orientations.
double axial_mean(const std::vector<double>& angles);
double axial_sd(const std::vector<double>& angles);

// The direction of an axial angle.
Vec2 direction_of(double angle);

// PCA of the points: axis = principal eigenvector, extents from the points' projections padded
// by `pad`, centre = middle of the extents (not the mean).
OrientedBox principal_box(const std::vector<Vec2>& points, double pad);

// For each point, the vector to its nearest other point (zero for a single point).
std::vector<Vec2> nearest_neighbour_vectors(const std::vector<Vec2>& points);

}  // namespace tw::detail
