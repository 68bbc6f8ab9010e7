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

// Whether the exemplar's lines cross other lines more often than they end on them: more nodes
// (not on its boundary) of degree 4 whose edges pair into two lines going on within `deflection`
// radians (a crossing) than nodes of degree 3 with one such pair (a T-junction). Trees drawn
// over each other cross; fields' boundaries end on each other.
bool lines_cross_more_than_they_end_on_lines(const Network& exemplar, double deflection);

}  // namespace tw::network_detail
