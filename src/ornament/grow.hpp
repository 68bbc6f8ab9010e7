#pragma once
// FloralSurf's space filling (Albano et al. 2023, Algorithm 1) over a heightfield window:
// ornaments grow element by element from a priority queue of growth points; at each point ten
// seeded random candidates are traced, those that cross a placed ornament, come within the
// set's clearance of one, enter a forbidden pixel or overlap a footprint to keep off (exactly,
// in vector space: ornament/footprints.hpp) are rejected, and the one farthest on
// average (heat-method geodesic distance) from what is placed wins. When the queue is empty
// the next ornament starts at the allowed point farthest from everything placed.
#include <cstdint>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "ornament/element.hpp"
#include "ornament/footprints.hpp"
#include "ornament/surface.hpp"

namespace tw {

enum class OrnamentAlignment {
  growth,   // each element follows its growth point's frame (the decoration's own shape)
  contour,  // each element's +x follows the contour direction (terraces along the slope)
};
enum class CandidateSelection {
  best_mean_distance,  // the paper's score S = mean geodesic distance to placed ornaments
  first_fit,           // the greedy variant of the paper's Figure 6 (first candidate that fits)
};

struct GrowthParams {
  std::uint64_t seed = 1;
  int trials = 10;  // candidates per growth point
  CandidateSelection selection = CandidateSelection::best_mean_distance;
  OrnamentAlignment alignment = OrnamentAlignment::growth;
  int max_ornaments = 32;
  int max_elements = 20000;
  // A new ornament starts only where the farthest allowed point is at least this far (metres)
  // from placed ornaments and forbidden ground; <= 0: max(2 clearance, scale / 2).
  double min_seed_distance_m = 0.0;
  int subdivision_depth = 3;
  // Each placed element's distances solved on the part of the mesh they can change (see
  // grow.cpp) instead of the whole mesh; false: the whole mesh every time (the reference).
  bool local_distances = true;
};

struct GrownLine {
  int ornament = 0;          // which ornament (tree of elements) it belongs to
  int element = 0;           // the placed element's serial number
  std::string name;          // the decorative element's name
  std::string material;      // the spline's material
  std::vector<Vec2> points;  // world metres
  std::vector<double> heights;
};

struct GrowthResult {
  std::vector<GrownLine> lines;
  int ornaments = 0, elements = 0;
  int rejected_crossing = 0, rejected_forbidden = 0, rejected_untraceable = 0;
  int rejected_footprint = 0;  // candidates that came onto a footprint of KeepOff
  // Heat-method solves after placing an element: on a part of the mesh, on the whole of it.
  int local_solves = 0, whole_solves = 0;
};

// Cells of a grid no line may pass through (a heightfield's nodata, on its own grid, which may
// be finer than the mesh's): nonzero in `allowed` where a line may go; outside `window` none.
struct ForbiddenCells {
  GridSpec grid;
  Window window;
  Raster<std::uint8_t> allowed;  // window-sized
};

// What the lines keep off exactly, on the vector lines a candidate would write (the mesh's
// `allowed` mask is coarser: a footprint narrower than its vertex spacing slips through it).
struct KeepOff {
  const FootprintIndex* footprints = nullptr;  // features read, lines grown before
  double half_width = 0.0;                     // the grown lines' own footprint, metres
  const ForbiddenCells* cells = nullptr;
};

// `allowed` is window-sized: nonzero where ornaments may go (inside the region, off avoided
// features). A candidate whose lines, buffered by keep_off.half_width, overlap a footprint of
// keep_off or pass through one of its forbidden cells is rejected like one that crosses a
// placed line. Deterministic: the same inputs and seed give the same lines, bit for bit.
GrowthResult grow_ornaments(const TerrainSurface& surface, const Raster<std::uint8_t>& allowed,
                            const ElementSet& set, const GrowthParams& params,
                            const KeepOff& keep_off = {});

// The fraction of allowed vertices within `radius_m` (heat-method geodesic distance) of a line.
double ornament_coverage(const TerrainSurface& surface, const Raster<std::uint8_t>& allowed,
                         const std::vector<GrownLine>& lines, double radius_m);

// Whether the segment a-b (world metres) passes through a pixel that is not allowed (or
// outside the window): the exact pixel traversal (Amanatides & Woo).
bool enters_forbidden(const GridSpec& grid, const Window& window,
                      const Raster<std::uint8_t>& allowed, Vec2 a, Vec2 b);

}  // namespace tw
