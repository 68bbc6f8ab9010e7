#include "terrain/detail/profiles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tw::detail {

std::vector<double> terrain_along(HeightSampler& heights, const Curve& curve, double step) {
  const auto cumulative = cumulative_lengths(curve);
  const double total = cumulative.back();
  const std::size_t count = std::size_t(std::llround(total / step)) + 1;
  std::vector<double> v(count);
  for (std::size_t i = 0; i < count; ++i)
    v[i] = heights.bilinear(point_at(curve, cumulative, std::min(total, i * step)));
  // Bridge nodata: linear between valid neighbours, constant beyond the first / last valid.
  std::size_t previous = count;
  for (std::size_t i = 0; i < count; ++i) {
    if (std::isnan(v[i])) continue;
    if (previous == count) {
      std::fill(v.begin(), v.begin() + std::ptrdiff_t(i), v[i]);
    } else {
      for (std::size_t k = previous + 1; k < i; ++k)
        v[k] = v[previous] + (v[i] - v[previous]) * double(k - previous) / double(i - previous);
    }
    previous = i;
  }
  if (previous == count) return {};
  std::fill(v.begin() + std::ptrdiff_t(previous) + 1, v.end(), v[previous]);
  return v;
}

std::vector<double> moving_average(const std::vector<double>& v, double step, double window) {
  const auto half = std::ptrdiff_t(std::floor(0.5 * window / step));
  if (half <= 0) return v;
  const auto n = std::ptrdiff_t(v.size());
  std::vector<double> prefix(v.size() + 1, 0.0);
  for (std::ptrdiff_t i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + v[i];
  std::vector<double> out(v.size());
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const std::ptrdiff_t lo = std::max<std::ptrdiff_t>(0, i - half);
    const std::ptrdiff_t hi = std::min(n, i + half + 1);
    out[i] = (prefix[hi] - prefix[lo]) / double(hi - lo);
  }
  return out;
}

std::vector<double> limit_grade(const std::vector<double>& v, double step, double grade) {
  const double rise = grade * step;
  std::vector<double> forward = v, backward = v;
  for (std::size_t i = 1; i < v.size(); ++i)
    forward[i] = std::clamp(forward[i], forward[i - 1] - rise, forward[i - 1] + rise);
  for (std::size_t i = v.size() - 1; i-- > 0;)
    backward[i] = std::clamp(backward[i], backward[i + 1] - rise, backward[i + 1] + rise);
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = 0.5 * (forward[i] + backward[i]);
  return out;
}

std::vector<double> moving_average_closed(const std::vector<double>& v, double step,
                                          double window) {
  if (v.size() < 3) return v;
  const auto n = std::ptrdiff_t(v.size() - 1);  // samples of one period
  const auto half = std::ptrdiff_t(std::floor(0.5 * window / step));
  std::vector<double> out(v.size());
  if (2 * half + 1 >= n) {
    double sum = 0.0;
    for (std::ptrdiff_t i = 0; i < n; ++i) sum += v[std::size_t(i)];
    std::fill(out.begin(), out.end(), sum / double(n));
    return out;
  }
  if (half <= 0) return v;
  // Prefix sums over three periods so every window [i - half, i + half] is one difference.
  std::vector<double> prefix(std::size_t(3 * n) + 1, 0.0);
  for (std::ptrdiff_t k = 0; k < 3 * n; ++k)
    prefix[std::size_t(k) + 1] = prefix[std::size_t(k)] + v[std::size_t(k % n)];
  for (std::ptrdiff_t i = 0; i < n; ++i)
    out[std::size_t(i)] =
        (prefix[std::size_t(n + i + half + 1)] - prefix[std::size_t(n + i - half)]) /
        double(2 * half + 1);
  out[std::size_t(n)] = out[0];
  return out;
}

std::vector<double> limit_grade_closed(const std::vector<double>& v, double step, double grade) {
  if (v.size() < 3) return v;
  const std::size_t n = v.size() - 1;
  const double rise = grade * step;
  // Two laps each way reach every sample from every other along the shorter side.
  std::vector<double> upper(v.begin(), v.end() - 1), lower = upper;
  for (int lap = 0; lap < 2; ++lap) {
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = k, previous = (k + n - 1) % n;
      upper[i] = std::max(upper[i], upper[previous] - rise);
      lower[i] = std::min(lower[i], lower[previous] + rise);
    }
  }
  for (int lap = 0; lap < 2; ++lap) {
    for (std::size_t k = n; k-- > 0;) {
      const std::size_t i = k, next = (k + 1) % n;
      upper[i] = std::max(upper[i], upper[next] - rise);
      lower[i] = std::min(lower[i], lower[next] + rise);
    }
  }
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < n; ++i) out[i] = 0.5 * (upper[i] + lower[i]);
  out[n] = out[0];
  return out;
}

std::vector<double> water_surface(const std::vector<double>& terrain, double step,
                                  double min_slope) {
  std::vector<double> s = terrain;
  for (std::size_t i = 1; i < s.size(); ++i) s[i] = std::min(s[i], s[i - 1] - min_slope * step);
  return s;
}

void apply_pins(std::vector<double>& v, double step, double grade, const std::vector<Pin>& pins,
                double period) {
  if (pins.empty()) return;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double s = double(i) * step;
    double upper = std::numeric_limits<double>::infinity();
    double lower = -upper;
    for (const Pin& p : pins) {
      double distance = std::abs(s - p.s);
      if (period > 0.0) {
        const double wrapped = std::fmod(distance, period);
        distance = std::min(wrapped, period - wrapped);
      }
      const double slack = grade * std::max(0.0, distance - p.flat);
      upper = std::min(upper, p.height + slack);
      lower = std::max(lower, p.height - slack);
    }
    // Inconsistent pins (too steep between them): the lower cone wins, deterministically.
    v[i] = std::max(std::min(v[i], upper), lower);
  }
}

}  // namespace tw::detail
