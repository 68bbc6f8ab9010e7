#pragma once
// How deep a carved river lies below the valley it runs in: the measure behind the river
// defaults (docs/terrain.md, "Conformance"), used by bench_conformance and the tests. A coarse
// line that crosses a spur is carved below the terrain under it; what a viewer sees as a
// trench is the bed's depth below the valley floor around the line, not below the spur.
#include "core/grid.hpp"
#include "ribbon/curve.hpp"

namespace tw {

struct TrenchProfile {
  double length = 0.0;         // metres of centreline measured (samples over valid cells)
  double deeper_length = 0.0;  // metres of it where the trench is deeper than the threshold
  double deepest = 0.0;        // metres: the deepest trench met
};

// Along `centerline` every half cell: the valley floor is the lowest cell of `before` within
// `floor_radius` metres of the point, the bed the bilinear height of `after` there; the trench
// is floor - bed. Nodata cells are never read as heights; points without a valid floor or bed
// are not measured.
TrenchProfile trench_below_valley_floor(const Raster<float>& before, const Raster<float>& after,
                                        const GridSpec& grid, const Curve& centerline,
                                        double floor_radius, double threshold);

}  // namespace tw
