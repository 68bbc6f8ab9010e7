#pragma once
// How strongly a feature holds a pixel at distance d (metres) from its centerline: the
// cross-section shared by height operations and splat weights.
#include <algorithm>
#include <cmath>

#include "terrain/features.hpp"

namespace tw::detail {

inline double smoothstep01(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// 1 up to `inner`, then a smooth fall to 0 over `ramp` metres.
inline double held_then_smooth(double d, double inner, double ramp) {
  if (d <= inner) return 1.0;
  if (ramp <= 0.0) return 0.0;
  return 1.0 - smoothstep01((d - inner) / ramp);
}

// Weight in [0, 1] with which the feature replaces the terrain's height.
inline double height_weight(const TerrainFeature& f, double d) {
  const double half = 0.5 * f.width;
  switch (f.kind) {
    case FeatureKind::road:
      return held_then_smooth(d, half + f.road.shoulder_width, f.road.falloff);
    case FeatureKind::river:
      return held_then_smooth(d, half, f.river.bank_width + f.river.falloff);
    case FeatureKind::ridge:
      return std::pow(held_then_smooth(d, half, f.ridge.falloff), f.ridge.sharpness);
  }
  return 0.0;
}

// The integral of held_then_smooth over [0, x], x >= 0 (smoothstep integrates to u^3 - u^4/2).
inline double held_then_smooth_integral(double x, double inner, double ramp) {
  if (x <= inner) return x;
  if (ramp <= 0.0) return inner;
  const double u = std::min(1.0, (x - inner) / ramp);
  return inner + ramp * (u - u * u * u + 0.5 * u * u * u * u);
}

// The height weight averaged across a pixel of `pixel` metres whose centre is d metres from
// the centreline (a box of one pixel across the line): a feature narrower than a cell changes
// it by the fraction it covers, not wholesale (docs/terrain.md, "Coarse grids").
inline double cell_height_weight(const TerrainFeature& f, double d, double pixel) {
  const double a = d - 0.5 * pixel, b = d + 0.5 * pixel;
  const double half = 0.5 * f.width;
  // The weight is even in the signed distance: integrate its odd antiderivative.
  auto integral = [&](double inner, double ramp, double x) {
    return std::copysign(held_then_smooth_integral(std::abs(x), inner, ramp), x);
  };
  switch (f.kind) {
    case FeatureKind::road: {
      const double inner = half + f.road.shoulder_width;
      return (integral(inner, f.road.falloff, b) - integral(inner, f.road.falloff, a)) / pixel;
    }
    case FeatureKind::river: {
      const double ramp = f.river.bank_width + f.river.falloff;
      return (integral(half, ramp, b) - integral(half, ramp, a)) / pixel;
    }
    case FeatureKind::ridge: {
      // No closed form under the power: the midpoint rule over 8 strips of the pixel.
      constexpr int kStrips = 8;
      double sum = 0.0;
      for (int i = 0; i < kStrips; ++i)
        sum += height_weight(f, std::abs(a + (i + 0.5) * pixel / kStrips));
      return sum / kStrips;
    }
  }
  return 0.0;
}

// Fraction of a pixel of size `pixel` metres, centred at distance d, inside the strip of
// half-width r around the centreline (a box of one pixel across the line: a one-pixel linear
// ramp across each edge, and the strip's share of the pixel when it is narrower than one).
inline double coverage(double d, double r, double pixel) {
  const double overlap = std::min(d + 0.5 * pixel, r) - std::max(d - 0.5 * pixel, -r);
  return std::clamp(overlap / pixel, 0.0, 1.0);
}

// The radii of a feature's two splat materials: inner (road / riverbed / ridge_rock) and
// outer (shoulder / bank; equal to inner for ridges, which have one material).
struct SplatRadii {
  double inner = 0.0;
  double outer = 0.0;
};
inline SplatRadii splat_radii(const TerrainFeature& f) {
  const double half = 0.5 * f.width;
  switch (f.kind) {
    case FeatureKind::road:
      return {half, half + f.road.shoulder_width};
    case FeatureKind::river:
      return {half, half + f.river.bank_width};
    case FeatureKind::ridge: {
      const double rock = half + 0.25 * f.ridge.falloff;
      return {rock, rock};
    }
  }
  return {half, half};
}

}  // namespace tw::detail
