#include "terrain/features.hpp"

#include <cmath>

#include "core/error.hpp"

namespace tw {

std::string_view to_string(FeatureKind kind) {
  switch (kind) {
    case FeatureKind::road:
      return "road";
    case FeatureKind::river:
      return "river";
    case FeatureKind::ridge:
      return "ridge";
  }
  return "unknown";
}

double feature_reach(const TerrainFeature& f) {
  const double half = 0.5 * f.width;
  switch (f.kind) {
    case FeatureKind::road:
      return half + f.road.shoulder_width + f.road.falloff;
    case FeatureKind::river:
      return half + f.river.bank_width + f.river.falloff;
    case FeatureKind::ridge:
      return half + f.ridge.falloff;
  }
  return half;
}

namespace {

void require(bool ok, const TerrainFeature& f, const char* what, double value) {
  if (!ok)
    fail("{} feature FID {}: {} out of range (got {})", to_string(f.kind), f.fid, what, value);
}

}  // namespace

void validate_feature(const TerrainFeature& f) {
  for (const Vec2 p : f.centerline.points) {
    if (!is_finite(p))
      fail("{} feature FID {}: non-finite centerline point", to_string(f.kind), f.fid);
  }
  if (without_duplicates(f.centerline).points.size() < 2)
    fail("{} feature FID {}: centerline needs at least two distinct points", to_string(f.kind),
         f.fid);
  require(std::isfinite(f.width) && f.width > 0.0, f, "width", f.width);
  switch (f.kind) {
    case FeatureKind::road:
      require(f.road.max_grade > 0.0 && std::isfinite(f.road.max_grade), f, "max_grade",
              f.road.max_grade);
      require(f.road.shoulder_width >= 0.0, f, "shoulder_width", f.road.shoulder_width);
      require(f.road.falloff >= 0.0 && std::isfinite(f.road.falloff), f, "falloff", f.road.falloff);
      require(f.road.smoothing >= 0.0 && std::isfinite(f.road.smoothing), f, "smoothing",
              f.road.smoothing);
      require(f.road.max_cut.value_or(0.0) >= 0.0, f, "max_cut", f.road.max_cut.value_or(0.0));
      require(f.road.max_fill.value_or(0.0) >= 0.0, f, "max_fill", f.road.max_fill.value_or(0.0));
      break;
    case FeatureKind::river:
      require(f.river.depth >= 0.0 && std::isfinite(f.river.depth), f, "depth", f.river.depth);
      require(f.river.bank_width >= 0.0, f, "bank_width", f.river.bank_width);
      require(f.river.falloff >= 0.0 && std::isfinite(f.river.falloff), f, "falloff",
              f.river.falloff);
      require(f.river.min_slope >= 0.0 && std::isfinite(f.river.min_slope), f, "min_slope",
              f.river.min_slope);
      require(max_carve(f.river) >= 0.0, f, "max_carve", max_carve(f.river));
      break;
    case FeatureKind::ridge:
      require(std::isfinite(f.ridge.height), f, "height", f.ridge.height);
      require(f.ridge.falloff >= 0.0 && std::isfinite(f.ridge.falloff), f, "falloff",
              f.ridge.falloff);
      require(f.ridge.sharpness > 0.0 && std::isfinite(f.ridge.sharpness), f, "sharpness",
              f.ridge.sharpness);
      break;
  }
}

}  // namespace tw
