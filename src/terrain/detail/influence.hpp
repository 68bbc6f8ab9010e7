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

// Fraction of a pixel of size `pixel` metres, centred at distance d, inside radius r
// (a one-pixel linear ramp across the edge).
inline double coverage(double d, double r, double pixel) {
  return std::clamp((r - d) / pixel + 0.5, 0.0, 1.0);
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
