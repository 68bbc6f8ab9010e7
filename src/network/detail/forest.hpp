#pragma once
// Traits of an exemplar whose lines end free and cross rather than close cells (a forest of
// stream trees; docs/networks.md, "Growth", steps 2 and 5), measured on the exemplar itself.
#include <vector>

#include "network/network.hpp"

namespace tw::network_detail {

// How much room the exemplar leaves between its lines: the `quantile` (0..1) of the distances from
// the centres of a lattice of `spacing` metres over the exemplar's nodes' bounding box to its
// nearest line; 0 for an exemplar without edges. A network of cells leaves little (about half a
// cell); a forest of trees leaves wide gaps between its branches, which growth seeding every gap of
// a median edge would fill.
double empty_space_quantile(const Network& exemplar, double spacing, double quantile);

// The exemplar's junctions (nodes not on its boundary) where a line goes on through: crossings
// (degree 4, whose edges pair into two lines going on within `deflection` radians) and
// T-junctions (degree 3 with one such pair), and all its junctions of degree 3. Fields' hedges
// end on each other in Ts; cracks in drying mud meet in Ys, none going on.
struct JunctionsGoingOn {
  int crossings = 0, t_junctions = 0, three_way = 0;
};
JunctionsGoingOn junctions_going_on(const Network& exemplar, double deflection);

// Whether the exemplar's lines cross other lines more often than they end on them: more
// crossings than T-junctions (junctions_going_on). Trees drawn
// over each other cross; fields' boundaries end on each other.
bool lines_cross_more_than_they_end_on_lines(const Network& exemplar, double deflection);

}  // namespace tw::network_detail
