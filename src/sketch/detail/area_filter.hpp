#pragma once
// The world half of area synthesis: candidates mapped into the map, kept inside the polygon,
// off forbidden cells, and apart from shapes they were disjoint from in the sketch (H3), one at
// a time as area_candidates hands them over.
#include <functional>
#include <memory>
#include <vector>

#include "raster/avoidance.hpp"
#include "raster/polygon.hpp"
#include "sketch/area_synthesis.hpp"
#include "sketch/detail/area_candidates.hpp"
#include "sketch/detail/domain_cover.hpp"

namespace tw::detail {

struct PlacementOptions {
  double scale = 1.0;
  // Not affine (a curved lead frame): `densify` > 0 is the longest segment of input space mapped
  // as a straight one, and shape axes are taken over that length.
  double densify = 0.0;
  // Unbounded strokes are cut where blocked to within `step` metres, tested in pieces of at
  // most `piece` metres, and simplified within `tolerance` metres (a simplified segment that
  // leaves the traced line tested again).
  double step = 0.0, piece = 0.0, tolerance = 0.0;
};

class Placer {
 public:
  // `avoidance` may be null (nothing forbidden); `h`, `domain`, `cover` and `avoidance` outlive
  // the placer.
  Placer(const SupportHierarchy& h, const Polygon& domain, const DomainCover& cover,
         std::function<Vec2(Vec2)> to_world, const SparseAvoidance* avoidance,
         const PlacementOptions& options);
  ~Placer();

  void place(const Candidate& candidate);
  AreaPattern take() { return std::move(out_); }
  AreaPattern& pattern() { return out_; }

 private:
  struct State;
  void place_bounded(const Candidate& c, ShapeInstance instance,
                     std::vector<std::vector<Vec2>> strokes, const std::vector<double>& widths,
                     Vec2 axis, double half_width);
  const SupportHierarchy& h_;
  const DomainCover& cover_;
  std::function<Vec2(Vec2)> to_world_;
  const SparseAvoidance* avoidance_;
  PlacementOptions options_;
  std::unique_ptr<State> state_;
  std::uint32_t next_ = 0;  // candidates seen
  AreaPattern out_;
};

}  // namespace tw::detail
