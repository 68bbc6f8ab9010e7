#include "ribbon/smooth.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace tw {

Curve smooth(const Curve& curve, double sigma_m) {
  if (!std::isfinite(sigma_m)) fail("smooth: window {} m is not finite", sigma_m);
  const Curve clean = without_duplicates(curve);
  if (sigma_m <= 0.0 || clean.points.size() < 3) return curve;
  const double total = arc_length(clean);
  // Uniform samples make the discrete Gaussian a true arc-length Gaussian.
  const Curve samples = resample(clean, std::max(sigma_m / 4.0, total / 200000.0));
  const auto& p = samples.points;
  const int n = int(p.size());
  const double spacing = total / double(clean.closed ? n : n - 1);
  int radius = int(std::ceil(3.0 * sigma_m / spacing));
  // A kernel longer than the curve would reflect more than once; truncating it stays symmetric.
  radius = std::min(radius, clean.closed ? n / 2 : n - 1);
  std::vector<double> weights(std::size_t(radius) + 1);
  double sum = 0.0;
  for (int k = 0; k <= radius; ++k) {
    const double u = k * spacing / sigma_m;
    weights[k] = std::exp(-0.5 * u * u);
    sum += k == 0 ? weights[k] : 2.0 * weights[k];
  }
  for (double& w : weights) w /= sum;

  // Open curves continue past each end by point reflection (C(-s) = 2 C(0) - C(s)): the ends
  // stay put and straight lines stay straight.
  auto sample = [&](int j) -> Vec2 {
    if (clean.closed) return p[std::size_t(((j % n) + n) % n)];
    if (j < 0) return p[0] * 2.0 - p[std::size_t(-j)];
    if (j >= n) return p[std::size_t(n - 1)] * 2.0 - p[std::size_t(2 * (n - 1) - j)];
    return p[std::size_t(j)];
  };
  Curve out;
  out.closed = clean.closed;
  out.points.resize(p.size());
  for (int i = 0; i < n; ++i) {
    Vec2 acc = p[std::size_t(i)] * weights[0];
    for (int k = 1; k <= radius; ++k) acc += (sample(i - k) + sample(i + k)) * weights[k];
    out.points[std::size_t(i)] = acc;
  }
  if (!clean.closed) {
    out.points.front() = clean.points.front();
    out.points.back() = clean.points.back();
  }
  return out;
}

}  // namespace tw
