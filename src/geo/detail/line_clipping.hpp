#pragma once
// Clipping a line (in the grid's CRS) to the grid's extent with GEOS (OGR Intersection).
#include <cstdint>
#include <vector>

#include "core/vec2.hpp"
#include "geo/detail/vector_layer.hpp"

namespace tw::detail {

struct ClippedLine {
  std::vector<Vec2> points;  // a closed ring does not repeat its first point
  bool closed = false;
};

// The pieces of `line` inside `extent`, in the line's direction. A line fully inside comes back
// whole (closed if it is a ring), vertices as they are (repair_line judges them); a line crossing
// the border comes back as the pieces inside, those meeting at a vertex joined again; a line fully
// outside gives no piece.
std::vector<ClippedLine> clip_line(const OGRLineString& line, const OGRPolygon& extent,
                                   const OpenVectorLayer& layer, std::int64_t fid);

}  // namespace tw::detail
