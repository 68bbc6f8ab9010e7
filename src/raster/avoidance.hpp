#pragma once
// The avoidance map (Zhou et al. 2013, Section 3.1): canvas pixels where no opaque exemplar pixel
// may land, plus the distance to them.
#include <cstdint>
#include <limits>
#include <vector>

#include "core/grid.hpp"
#include "raster/polygon.hpp"
#include "raster/sparse_raster.hpp"
#include "ribbon/ribbon.hpp"

namespace tw {

struct AvoidanceMap {
  GridSpec grid;
  Window window;
  Raster<std::uint8_t> forbidden;  // window-sized, 1 = forbidden, 0 = free
  Raster<float> distance;          // metres to the nearest forbidden pixel centre (0 on them)
};

struct AvoidanceInputs {
  std::vector<Polygon> polygons;         // existing areas (lakes, buildings...)
  std::vector<std::vector<Vec2>> lines;  // existing linear features
  std::vector<double> line_widths;       // full widths in metres, one per line
  std::vector<const Ribbon*> ribbons;    // already synthesized features: whole footprint
  bool include_foldovers = true;         // add fold-overs of `ribbons` and `current`
  const Ribbon* current = nullptr;       // the ribbon about to be synthesized: fold-overs only
  std::vector<Polygon> junction_discs;   // e.g. from junction_discs() (docs/junctions.md)
};

// Union of everything in `inputs` on the window (pixel-centre rule), and its exact Euclidean
// distance field capped at `max_distance` metres. A finite cap makes the window's result equal
// the crop of any larger window's (it reads a halo of the cap around the window); infinity
// gives the distance within the window only. Throws tw::Error (naming the line) on mismatched
// widths, and on max_distance <= 0.
AvoidanceMap build_avoidance_map(const AvoidanceInputs& inputs, const GridSpec& grid,
                                 const Window& window,
                                 double max_distance = std::numeric_limits<double>::infinity());

// The forbidden cells of a canvas whose box is far larger than what it serves (an area's polygon,
// docs/shape-patterns.md): tiles over `grid` held only where something is forbidden, every other
// cell free. Memory follows what is forbidden near the polygon, not the polygon's box.
struct SparseAvoidance {
  GridSpec grid;
  SparseRaster<std::uint8_t> forbidden;
};

// True when every forbidden cell centre lies farther than `half_width` metres from the segment
// pq: a stroke of that width drawn there touches no forbidden cell (burn_buffered_lines' pixel-
// centre rule). Exact; reads the cells of the segment's box grown by half_width, so callers keep
// segments short where the canvas is busy.
bool segment_clear(const SparseAvoidance& avoidance, Vec2 p, Vec2 q, double half_width);

// The same union (no distance field) on the allocated tiles of `forbidden`, a sparse canvas over
// `grid`: equal to build_avoidance_map's mask there.
void burn_avoidance(const AvoidanceInputs& inputs, const GridSpec& grid,
                    SparseRaster<std::uint8_t>& forbidden);

}  // namespace tw
