#pragma once
// The global layout of an exemplar (docs/networks.md, "Layout"): its long strokes, lines that go
// on nearly straight across junctions for a large part of the exemplar's extent (the tracks of
// a grid of fields, the walls of terraces, the rings and spokes of a radial network). Local
// growth does not make them; the layout copies them first and grows the rest from their
// junctions.
#include <vector>

#include "network/network.hpp"

namespace tw::network_detail {

// Heading (radians) leaving an end of a polyline along its first distinct segment.
double leaving_heading(const std::vector<Vec2>& points, bool from_start);

// Per exemplar edge: the length of its stroke (edges chained across junctions, each the
// other's least deflected continuation within `deflection` radians) when that is at least
// `min_fraction` of the exemplar's longer side, else 0. All 0 when such strokes hold less than
// `min_share` of the exemplar's length (no global structure worth laying out).
std::vector<double> long_stroke_edges(const Network& exemplar, double deflection,
                                      double min_fraction, double min_share);

}  // namespace tw::network_detail
