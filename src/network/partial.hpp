#pragma once
// A partial network (docs/networks.md, "Complete and clone"): the user's lines, kept exactly as
// drawn, checked and noded into the graph growth completes. One reading for `network complete`,
// the drawing page and a pipeline's `network: partial:`; a clone's map lines in its target are
// map data, noded instead (kept_map_network).
#include <string>
#include <vector>

#include "core/warnings.hpp"
#include "network/exemplar.hpp"

namespace tw {

// The lines as a planar graph (T-junctions noded, every edge kept = true). Throws tw::Error
// "<subject> <source>: FID n: outside the region" for a line not inside `region`,
// "...: FID n crosses itself" and "...: FID n crosses FID m" for lines meeting elsewhere than
// where a line ends (a loop closed at its own end is no crossing).
Network partial_network(const NetworkLines& lines, const std::vector<Polygon>& region,
                        const std::string& subject, const std::string& source, Warnings& warnings);

// The map's lines already in a clone's target: map data, noded like an exemplar
// (build_planar_network: ends within `snap_m` of another line snapped onto it, duplicates
// dropped), not held to a drawing's rule: lines crossing where neither ends are noded into a
// junction there, a warning "crossing_lines" naming both FIDs. Every edge is kept = true.
Network kept_map_network(const NetworkLines& lines, double snap_m, const std::string& subject,
                         Warnings& warnings);

}  // namespace tw
