#pragma once
// Cleaning one clipped line: near-duplicate vertices, spikes and tiny loops (docs/pipeline.md,
// "repair"). Self-intersections are found by GEOS through OGR; what is left crossing itself
// after the repair is a genuine self-crossing and stays.
#include <string>
#include <vector>

#include "core/vec2.hpp"
#include "geo/features.hpp"
#include "geo/line_repair_memo.hpp"

namespace tw::detail {

// "removed 3 duplicate vertices, 1 spike, 1 loop of 0.8 m" (only what changed).
std::string describe(const LineRepairCounts& counts);

// Repairs `points` in place (a closed ring does not repeat its first point; its first vertex
// stays). Returns false when nothing with length is left (the piece is to be dropped); `points`
// is then empty, which the repair memo relies on to store a dropped piece as no points (it keeps
// the points, not the verdict). Throws tw::Error when GEOS cannot node a line that meets itself.
bool repair_line(std::vector<Vec2>& points, bool closed, const LineRepair& options,
                 LineRepairCounts& counts);

}  // namespace tw::detail
