#pragma once
// Conformance of a vector line to the DEM: a river centreline drawn at 1:250 000 crosses the
// spurs of a 90 m DEM; moving it onto the valley floor (or a ridge line onto its crest) within
// a corridor keeps the carve shallow. The method is a least-cost path over the DEM cells of the
// corridor (docs/terrain.md, "Conformance", cites the stream-burning literature behind it).
#include <vector>

#include "core/grid.hpp"
#include "geo/height_sampler.hpp"
#include "ribbon/curve.hpp"

namespace tw {

enum class ConformTarget { valley_floor, crest };

struct ConformOptions {
  double corridor = 0.0;  // metres either side of the line; <= 0: the line is kept
  ConformTarget target = ConformTarget::valley_floor;
};

struct ConformResult {
  Curve line;                     // the conformed line; the given one when not moved
  bool conformed = false;         // false: kept as given (see `kept_because`)
  const char* kept_because = "";  // why not conformed (closed, over nodata, ...), "" otherwise
  double max_move = 0.0;          // metres: the largest distance between the two lines
  // metres: the farthest the conformed line lies from the given one (within the corridor, up
  // to a cell's diagonal); max_move can be larger where the path cuts across a drawn bend.
  double max_offset = 0.0;
  double mean_move = 0.0;         // metres: mean distance of the conformed line from the given one
};

// The least-cost 8-connected path over the cells within `corridor` metres of the line, from
// the cell of its first point on the grid to the cell of its last, smoothed; those two points
// keep their exact positions (clipped ends and junctions stay where they are). Nodata costs
// more than any path over valid cells: the path's length over nodata is the least the
// corridor allows (none where a valid path exists), then its cost is the least; nothing is
// carved over nodata, so a river drawn along the DEM's nodata edge keeps to the valid side.
// Closed lines and corridors wholly over nodata are kept as given. Deterministic (ties
// broken by the lowest cell index).
ConformResult conform_line(HeightSampler& heights, const Curve& line,
                           const ConformOptions& options);
// The same over `height`, which covers the whole grid.
ConformResult conform_line(const Raster<float>& height, const GridSpec& grid, const Curve& line,
                           const ConformOptions& options);

// A tributary drawn ending on a trunk's interior still meets it after conformance: each end
// of line i that lay within `tolerance[i]` metres of the interior of another line j as drawn
// (and not near one of j's ends, which conformance keeps) moves to the nearest point of j as
// conformed. `drawn` and `conformed` are parallel; lines kept as drawn are left alone.
void reattach_ends(const std::vector<Curve>& drawn, std::vector<Curve>& conformed,
                   const std::vector<double>& tolerance);

// The nearest point of the polyline to `p`, and the distance to it in metres.
Vec2 nearest_point(const Curve& line, Vec2 p);
double distance_to_line(const Curve& line, Vec2 p);

}  // namespace tw
