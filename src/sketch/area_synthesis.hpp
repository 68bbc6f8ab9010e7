#pragma once
// Synthesis of a structured shape-pattern over a map polygon (Olivier, Memari & Cani,
// Section 5, adapted to maps: docs/shape-patterns.md). The input space is laid at the polygon's
// centroid (the sketch is kept as drawn there), rotated to the lead bearing; lead directions are
// repeated with gaps from their recorded range, fibre medians copied and perturbed within their
// displacement areas (bent smoothly, never beyond half the gap to a neighbour), bounded shapes
// repeated along their fibres, unbounded strokes extended (lines, rays; arcs and curves by
// mirror duplication). Nothing leaves the polygon, touches a forbidden pixel, or overlaps a
// shape it was disjoint from in the sketch (H3).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "raster/avoidance.hpp"
#include "raster/polygon.hpp"
#include "sketch/hierarchy.hpp"

namespace tw {

// A lead direction field: at a world point, the angle (radians counter-clockwise from +x, modulo
// pi) the rows follow there; none where it is undefined (flat ground), where rows go straight on.
using LeadField = std::function<std::optional<double>(Vec2)>;

struct AreaSynthesisParams {
  double scale = 10.0;     // metres per input-space unit (the sketch covers scale x scale m)
  double bearing = 0.0;    // radians, counter-clockwise from +x: the input space's +x axis
  std::uint64_t seed = 1;  // same seed, same result
  double jitter = 0.5;     // fraction of each allowed displacement used, in [0, 1]
  bool keep_input = true;  // the sketch itself, unperturbed, at the centroid
  // Empty: the input space is laid straight along `bearing`. Otherwise its rows curve with the
  // field (detail/field_frame.hpp), starting along `bearing` at the centroid (the field's value
  // there, as a rule); `lead_step` metres between the frame's nodes (0: scale / 16, coarser for
  // polygons wider than 512 steps from the centroid).
  LeadField lead_field;
  double lead_step = 0.0;
  // Metres: unbounded strokes are written simplified within this (Douglas-Peucker); a
  // simplified segment that leaves the traced line is tested again (forbidden cells, other
  // shapes), and where it fails the traced points stay. 0: a quarter of the avoidance cell, or
  // scale / 400 without avoidance.
  double tolerance = 0.0;
};

// One placed shape: where engines put an instance of it.
struct ShapeInstance {
  int shape = 0;          // index into SupportHierarchy::shapes
  int lead = 0;           // the lead direction it was repeated in
  Vec2 position;          // world metres: centre of its oriented box
  double rotation = 0.0;  // radians, of its box axis
  double scale = 1.0;     // metres per input-space unit
  std::string material;   // of its first stroke
  bool unbounded = false;
};

struct PlacedStroke {
  std::vector<Vec2> points;  // world metres
  std::string material;
  double width = 0.0;  // metres
  int instance = 0;    // index into AreaPattern::instances
};

struct AreaPattern {
  std::vector<ShapeInstance> instances;
  std::vector<PlacedStroke> strokes;
  // Candidates left out, by reason.
  int outside = 0, forbidden = 0, overlapping = 0;
};

// `avoidance` may be null (nothing forbidden). Throws tw::Error for an empty polygon or a
// scale <= 0. Work and memory follow the shapes placed: candidates are made one at a time and
// only near the polygon, tested on a bounded lattice over it (detail/domain_cover.hpp), and an
// unbounded stroke costs its vertices and pieces, not its length in cells.
AreaPattern synthesize_area(const SupportHierarchy& hierarchy, const Polygon& domain,
                            const AreaSynthesisParams& params,
                            const SparseAvoidance* avoidance = nullptr);

// What synthesize_area will hold for a polygon, from its area and the sketch's density (bounded
// shapes per sketch square, unbounded stroke length per square metre), before anything is made:
// callers refuse a polygon that would not fit (a clear error instead of a bad_alloc).
// `cell`: the avoidance lattice's cell in metres (0: none).
struct AreaEstimate {
  double shapes = 0.0;  // bounded shapes and unbounded strokes' tested pieces
  double bytes = 0.0;
};
AreaEstimate estimate_area(const SupportHierarchy& hierarchy, const Polygon& domain,
                           const AreaSynthesisParams& params, double cell);

// The area of a polygon (outer ring less its holes), square metres.
double polygon_area(const Polygon& polygon);

// Where the input space's centre is laid: the area centroid of the outer ring (holes ignored).
Vec2 area_anchor(const Polygon& domain);

// The bearing of the polygon's long axis (principal axis of its outer ring's vertices,
// boundary-sampled so that vertex density does not bias it), in [0, pi).
double long_axis_bearing(const Polygon& domain);

// Hybridization (Section 6): the alignments of `structure` with the shapes of `shapes`. Each
// bounded shape of a structure fibre is replaced by the donor's bounded shapes in turn, centred
// where it was, turned from the donor's fibre to the structure's and scaled down where it would
// not fit between its neighbours; the result (a sketch of these strokes plus the structure's
// unbounded ones) is analysed again, so it is a hierarchy like any other.
SupportHierarchy hybridize(const SupportHierarchy& structure, const SupportHierarchy& shapes,
                           const AnalysisParams& params = {});

}  // namespace tw
