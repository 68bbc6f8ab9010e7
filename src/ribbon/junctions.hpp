#pragma once
// Where curves meet: shared endpoints, T-junctions and crossings. See docs/junctions.md for what
// the rest of the pipeline does with them.
#include <cstddef>
#include <limits>
#include <vector>

#include "geo/structure.hpp"
#include "ribbon/curve.hpp"

namespace tw {

struct JunctionMember {
  std::size_t curve = 0;     // index into the input curves
  double arc_length = 0.0;   // where on that curve, metres from its first point
  bool at_endpoint = false;  // the curve starts or ends here (never true for closed curves)
  friend bool operator==(const JunctionMember&, const JunctionMember&) = default;
};

struct Junction {
  Vec2 position;                        // mean of the meeting points
  std::vector<JunctionMember> members;  // sorted by (curve, arc_length); at least two
  // True when at least two members pass through (an X crossing); false when all but at most one
  // member end here (shared endpoints, T-junctions).
  bool crossing = false;
};

// Finds the junctions of a set of curves:
//  - endpoints of open curves closer than `tolerance_m` to each other (shared endpoints), or to
//    another curve (T-junctions: the other curve's member has at_endpoint = false);
//  - segment crossings between different curves, and self-crossings of one curve between
//    non-adjacent segments.
// Candidates closer than tolerance_m are merged into one junction (transitively). Segment pairs
// are found through a uniform grid, not by testing all pairs. Output order is deterministic
// (by first member). Throws tw::Error if tolerance_m < 0 or a point is not finite (names the
// curve).
std::vector<Junction> find_junctions(const std::vector<Curve>& curves, double tolerance_m);

// An axis-aligned box, metres (empty: min above max).
struct Extent {
  Vec2 min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2 max{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  friend bool operator==(const Extent&, const Extent&) = default;
};

// find_junctions, with each junction's extent in `extents`: the box of the meeting points merged
// into it, what a search over changed curves alone needs (junction_search.hpp).
std::vector<Junction> find_junctions(const std::vector<Curve>& curves, double tolerance_m,
                                     std::vector<Extent>& extents);

// The order find_junctions returns junctions in: by first member (curve, arc length), then
// position.
bool junction_precedes(const Junction& a, const Junction& b);

// What a curve is, vertically: on the ground or a bridge / tunnel, and its layer.
struct CurveLevel {
  Structure structure = Structure::ground;
  int layer = 0;
};

// The junctions where curves meet on the ground (docs/osm.md): a member passing through on a
// bridge or in a tunnel is dropped (it passes over or under), and the other members meet only
// with members of their own layer. Members that all end there always meet, whatever their
// layers (OSM ways join at a bridge's ends). A junction left with fewer than two members is
// dropped; `crossing` is recomputed. levels[i] is curve i's.
std::vector<Junction> at_grade(const std::vector<Junction>& junctions,
                               const std::vector<CurveLevel>& levels);

}  // namespace tw
