#pragma once
// Polylines cut by an axis-aligned box (the baselines' exemplar squares, the quilt's blocks and
// cells: docs/networks.md, "Quality" and "Quilting").
#include <vector>

#include "core/vec2.hpp"

namespace tw::network_detail {

// The parts of `pts` inside the box [lo, hi], each cut exactly at the box's sides, appended to
// `out`.
void cut_to_box(const std::vector<Vec2>& pts, Vec2 lo, Vec2 hi,
                std::vector<std::vector<Vec2>>& out);

}  // namespace tw::network_detail
