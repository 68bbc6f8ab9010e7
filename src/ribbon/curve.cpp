#include "ribbon/curve.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace tw {

std::vector<double> cumulative_lengths(const Curve& curve) {
  std::vector<double> cumulative;
  const auto& p = curve.points;
  cumulative.reserve(p.size() + 1);
  double total = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (i > 0) total += distance(p[i - 1], p[i]);
    cumulative.push_back(total);
  }
  if (curve.closed && p.size() > 1) cumulative.push_back(total + distance(p.back(), p.front()));
  return cumulative;
}

double arc_length(const Curve& curve) {
  const auto c = cumulative_lengths(curve);
  return c.empty() ? 0.0 : c.back();
}

Vec2 point_at(const Curve& curve, const std::vector<double>& cumulative, double x) {
  const auto& p = curve.points;
  if (p.empty()) fail("point_at: empty curve");
  const double total = cumulative.back();
  if (total <= 0.0) return p.front();
  if (curve.closed) {
    x = std::fmod(x, total);
    if (x < 0) x += total;
  } else {
    x = std::clamp(x, 0.0, total);
  }
  // Segment k runs from cumulative[k] to cumulative[k+1].
  auto it = std::upper_bound(cumulative.begin(), cumulative.end(), x);
  std::size_t k = it == cumulative.begin() ? 0 : std::size_t(it - cumulative.begin()) - 1;
  k = std::min(k, cumulative.size() - 2);
  const Vec2 a = p[k];
  const Vec2 b = p[(k + 1) % p.size()];
  const double seg = cumulative[k + 1] - cumulative[k];
  return seg > 0.0 ? lerp(a, b, (x - cumulative[k]) / seg) : a;
}

Vec2 tangent_at(const Curve& curve, const std::vector<double>& cumulative, double x, double h) {
  const double total = cumulative.back();
  double x0 = x - h, x1 = x + h;
  if (!curve.closed) {
    x0 = std::max(0.0, x0);
    x1 = std::min(total, x1);
  }
  return normalized(point_at(curve, cumulative, x1) - point_at(curve, cumulative, x0));
}

Curve resample(const Curve& curve, double step) {
  if (!(step > 0.0)) fail("resample: step must be > 0 (got {})", step);
  const auto cumulative = cumulative_lengths(curve);
  const double total = cumulative.back();
  Curve out;
  out.closed = curve.closed;
  const auto count = std::max<std::int64_t>(1, std::int64_t(std::ceil(total / step - 1e-9)));
  // Uniform spacing that fits the length exactly, so no tiny last segment appears.
  const double spacing = total / double(count);
  for (std::int64_t i = 0; i < count; ++i) out.points.push_back(point_at(curve, cumulative, i * spacing));
  if (!curve.closed) out.points.push_back(curve.points.back());
  return out;
}

Curve without_duplicates(const Curve& curve, double epsilon) {
  Curve out;
  out.closed = curve.closed;
  for (const Vec2 p : curve.points) {
    if (out.points.empty() || distance(out.points.back(), p) > epsilon) out.points.push_back(p);
  }
  if (out.closed && out.points.size() > 1 && distance(out.points.back(), out.points.front()) <= epsilon)
    out.points.pop_back();
  return out;
}

}  // namespace tw
