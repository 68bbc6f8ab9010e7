#pragma once
// A curvilinear frame that follows a lead direction field (sketch/area_synthesis.hpp), so that
// the rows of a pattern curve with the field instead of running straight across the polygon.
#include <vector>

#include "core/vec2.hpp"
#include "sketch/area_synthesis.hpp"

namespace tw::detail {

// Metres (u, v) from an anchor: the axis v = 0 is the field's streamline through the anchor
// (started along `bearing`), and each line u = const is the curve across the field (the
// normal's streamline) from the axis point at arc length u, parametrized by arc length v. A row
// of the sketch (v = const) is then a curve at constant distance from the axis measured along
// the normals: on a cone's contour field, a circle about the apex. Traced with the midpoint
// rule on a lattice of `step` metres out to `reach` on every side; mapped bilinearly between
// the lattice's nodes (linearly extrapolated beyond it). Where the field is undefined, curves
// go straight on.
class FieldFrame {
 public:
  FieldFrame(Vec2 anchor, double bearing, const LeadField& field, double reach, double step);

  Vec2 to_world(Vec2 uv) const;
  double step() const { return step_; }
  // The (u, v) range of the lattice's nodes that fall inside the box [lo, hi] of world
  // coordinates (the anchor's (0, 0) at least).
  void extent_within(Vec2 lo, Vec2 hi, Vec2& uv_lo, Vec2& uv_hi) const;

 private:
  Vec2 node(int i, int j) const { return nodes_[std::size_t(j) * side_ + std::size_t(i)]; }
  double step_;
  int half_ = 0;             // nodes from the anchor to the lattice's edge
  std::size_t side_ = 1;     // 2 * half_ + 1
  std::vector<Vec2> nodes_;  // row-major: j (v) major, i (u) minor
};

}  // namespace tw::detail
