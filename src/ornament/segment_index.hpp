#pragma once
// The lines of the ornaments placed so far, bucketed on a uniform grid, with CGAL's exact
// predicates for crossings (the paper tests intersections per triangle; on a heightfield the
// map projection is one-to-one, so crossings on the surface are crossings of the projections).
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "core/vec2.hpp"

namespace tw {

class SegmentIndex {
 public:
  explicit SegmentIndex(double cell_m);
  ~SegmentIndex();
  SegmentIndex(SegmentIndex&&) noexcept;

  // Whether the polyline crosses a stored segment or passes within `clearance` metres of one.
  // The joint (where a new element hangs from its parent) is exempt: segments may meet there
  // end to end, and segments with an end within `clearance` of it skip the clearance test.
  bool conflicts(const std::vector<Vec2>& polyline, Vec2 joint, double clearance) const;
  void insert(const std::vector<Vec2>& polyline);
  std::size_t size() const { return segments_.size(); }

 private:
  struct Segment {
    Vec2 a, b;
  };
  std::int64_t key(int cx, int cy) const { return (std::int64_t(cx) << 32) ^ std::uint32_t(cy); }
  double cell_;
  std::vector<Segment> segments_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

}  // namespace tw
