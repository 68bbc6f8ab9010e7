#pragma once
// Whether a line feature lies on the ground or passes over or under it, and its vertical
// layer: OSM's bridge / tunnel / layer conventions, read from columns of any source
// (docs/osm.md, "Bridges and tunnels").
#include <string_view>

namespace tw {

enum class Structure { ground, bridge, tunnel };

std::string_view to_string(Structure structure);

// Whether two features meet where one passes through the other (a crossing or a T-junction):
// only ground features on the same layer do. A bridge passes over what it crosses, a tunnel
// under it. (Features meeting end to end, as OSM ways do at a bridge's ends, always meet.)
bool meet_at_grade(Structure a, int layer_a, Structure b, int layer_b);

}  // namespace tw
