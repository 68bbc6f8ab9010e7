#pragma once
// An exemplar's border (docs/networks.md, "Growth", step 7: whole cells): whether its lines run
// along the whole perimeter of its extent (a map of fields with its outer hedge drawn as a frame),
// as opposed to a border made of its outermost cells' own sides.
#include "network/network.hpp"

namespace tw::network_detail {

// Whether the exemplar's lines come within `tolerance` of at least `share` of the perimeter of
// its nodes' bounding box (sampled).
bool has_drawn_frame(const Network& exemplar, double tolerance, double share);

}  // namespace tw::network_detail
