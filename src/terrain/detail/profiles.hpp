#pragma once
// Longitudinal profiles: the terrain sampled along a centerline, smoothed, graded (roads) or
// made non-increasing downstream (rivers). All in double; samples every `step` metres.
#include <vector>

#include "core/grid.hpp"
#include "geo/height_sampler.hpp"
#include "ribbon/curve.hpp"

namespace tw::detail {

// Heights every `step` metres along the curve (step divides L: count = L/step + 1);
// nodata gaps are bridged linearly between valid samples, ends extended. Returns an empty
// vector when the whole curve lies over nodata.
std::vector<double> terrain_along(HeightSampler& heights, const Curve& curve, double step);

// Centred moving average over `window` metres (truncated at the ends).
std::vector<double> moving_average(const std::vector<double>& v, double step, double window);

// The average of the forward- and backward-limited profiles: |v[i+1] - v[i]| <= grade*step,
// without a bias towards either direction.
std::vector<double> limit_grade(const std::vector<double>& v, double step, double grade);

// The same for a closed curve, whose samples 0 and n-1 are the same point: the profile is
// periodic (out[0] == out[n-1]) and the grade also holds across the closing point.
// Moving average: centred, wrapping around the loop (a window longer than the loop is the mean).
std::vector<double> moving_average_closed(const std::vector<double>& v, double step, double window);
// Grade limit: the mean of the lowest r-Lipschitz profile above v and the highest below it,
// r = grade * step and distances measured around the loop (both envelopes are within grade,
// so their mean is too).
std::vector<double> limit_grade_closed(const std::vector<double>& v, double step, double grade);

// Running minimum downstream with a minimum drop of min_slope per metre.
std::vector<double> water_surface(const std::vector<double>& terrain, double step,
                                  double min_slope);

// A pinned profile height (a junction) at arc length s, held level `flat` metres either side.
struct Pin {
  double s = 0.0;
  double height = 0.0;
  double flat = 0.0;
};
// Clamps a grade-limited profile between the cones of its pins, so it passes through each
// pin and stays within the grade (when the pins themselves are within grade of each other).
// `period` > 0: a closed curve of that length, distances to the pins measured around it.
void apply_pins(std::vector<double>& v, double step, double grade, const std::vector<Pin>& pins,
                double period = 0.0);

// Linear interpolation of a profile at arc length s (clamped to its ends).
template <class T>
double profile_at(const std::vector<T>& v, double step, double s) {
  const double x = std::max(0.0, s / step);
  const std::size_t i = std::min(std::size_t(x), v.size() - 1);
  if (i + 1 >= v.size()) return v.back();
  const double t = x - double(i);
  return v[i] + (double(v[i + 1]) - v[i]) * t;
}

}  // namespace tw::detail
