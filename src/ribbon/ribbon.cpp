#include "ribbon/ribbon.hpp"

#include <cmath>

#include "core/error.hpp"

namespace tw {

Ribbon make_ribbon(const Curve& input, const RibbonParams& params) {
  if (!(params.width > 0.0)) fail("ribbon width must be > 0 (got {} m)", params.width);
  if (!(params.delta > 0.0)) fail("ribbon delta must be > 0 (got {} m)", params.delta);
  const Curve curve = without_duplicates(input);
  if (curve.points.size() < 2) fail("curve has fewer than two distinct points");
  const auto cumulative = cumulative_lengths(curve);
  const double total = cumulative.back();
  if (total < params.delta)
    fail("curve is {:.3f} m long, shorter than delta = {} m", total, params.delta);

  Ribbon ribbon;
  ribbon.centerline = curve;
  ribbon.width = params.width;
  ribbon.delta = params.delta;
  ribbon.closed = curve.closed;

  const double h = params.tangent_window > 0.0 ? params.tangent_window : params.delta / 2.0;
  const auto count = std::int64_t(std::ceil(total / params.delta - 1e-9));
  std::vector<double> xs;
  for (std::int64_t i = 0; i < count; ++i) xs.push_back(double(i) * params.delta);
  xs.push_back(total);

  std::vector<Vec2> tops, bottoms;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    // The closing boundary of a closed curve is exactly its opening one.
    const double x = (curve.closed && i + 1 == xs.size()) ? 0.0 : xs[i];
    const Vec2 c = point_at(curve, cumulative, x);
    const Vec2 n = perp(tangent_at(curve, cumulative, x, h));
    tops.push_back(c + n * (params.width / 2.0));
    bottoms.push_back(c - n * (params.width / 2.0));
  }
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    ribbon.pieces.push_back({tops[i], bottoms[i], bottoms[i + 1], tops[i + 1], xs[i], xs[i + 1]});
  }
  return ribbon;
}

}  // namespace tw
