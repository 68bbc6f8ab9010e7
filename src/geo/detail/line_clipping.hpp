#pragma once
// Clipping lines with GEOS (OGR Intersection): near the grid in the layer's CRS before they are
// transformed, then exactly to the grid's extent in the grid's CRS.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/vec2.hpp"
#include "geo/detail/vector_layer.hpp"

namespace tw::detail {

struct ClippedLine {
  std::vector<Vec2> points;  // a closed ring does not repeat its first point
  bool closed = false;
};

// The parts of `parts` (in the layer's CRS) cut to `box` (grid_box_in_layer_crs): a part inside
// is kept as it is, one outside dropped, one crossing the border cut into its pieces inside.
std::unique_ptr<OGRMultiLineString> cut_to_box(const OGRMultiLineString& parts,
                                               const OGREnvelope& box, const OpenVectorLayer& layer,
                                               std::int64_t fid);

// The pieces of `line` inside `extent`, in the line's direction. A line fully inside comes back
// whole (closed if it is a ring), vertices as they are (repair_line judges them); a line crossing
// the border comes back as the pieces inside, those meeting at a vertex joined again; a line fully
// outside gives no piece.
std::vector<ClippedLine> clip_line(const OGRLineString& line, const OGRPolygon& extent,
                                   const OpenVectorLayer& layer, std::int64_t fid);

}  // namespace tw::detail
