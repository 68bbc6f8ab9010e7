#pragma once
// Smoothing of centerlines before slicing: digitized roads and rivers are jagged at the scale of
// a ribbon piece, and jagged normals make pieces fold over (Zhou et al. 2013, Section 3.1).
#include "ribbon/curve.hpp"

namespace tw {

// Arc-length Gaussian smoothing with standard deviation `sigma_m` metres (kernel cut at 3 sigma).
// The curve is first resampled uniformly (spacing sigma_m / 4, at most 200 000 points), so the
// result does not depend on how densely the input was digitized. Open curves keep both endpoints
// exactly (the curve is point-reflected about each end, which also keeps straight lines straight);
// closed curves wrap around. sigma_m <= 0 or fewer than 3 points returns the curve unchanged.
// Throws tw::Error if sigma_m is not finite.
Curve smooth(const Curve& curve, double sigma_m);

}  // namespace tw
