#pragma once
// Bridges and tunnels in the terrain plan (docs/osm.md, "Bridges and tunnels"): the ground
// roads they join are graded as if the structure were not there, and the structure's deck runs
// straight between the graded heights at its two ends.
#include <vector>

#include "terrain/detail/junctions.hpp"
#include "terrain/features.hpp"

namespace tw::detail {

// Removes the end contacts between a road and a bridge or tunnel road (both directions): a
// road ending at a bridge is not pinned to the bridge, the bridge follows the road. Also a road
// ending on the side of a road on another layer (not a T-junction). Rivers keep theirs, so a
// culvert still links its stream's reaches.
void drop_road_structure_contacts(const std::vector<TerrainFeature>& features,
                                  std::vector<std::vector<EndContact>>& contacts);

// Replaces the profile of every bridge or tunnel road by its deck: straight, by arc length,
// between the heights at the outer ends of its chain (structures joined end to end, as when OSM
// splits a bridge into several ways; usually just itself). Each outer end's height is the mean
// of the ground roads' profiles touching it (at the touch), else the structure's own profile
// end (the graded terrain there). `contacts` are the unfiltered end contacts.
void lay_decks(const std::vector<TerrainFeature>& features, const std::vector<double>& steps,
               const std::vector<std::vector<EndContact>>& contacts,
               std::vector<std::vector<double>>& profiles);

}  // namespace tw::detail
