#pragma once
// Junctions as forbidden discs for the avoidance map (docs/junctions.md).
#include <vector>

#include "raster/polygon.hpp"
#include "ribbon/junctions.hpp"

namespace tw {

// One regular polygon per junction, circumscribing the disc of radii[i] metres around
// junctions[i].position (so the whole disc is covered), with `sides` sides (>= 8).
// Throws tw::Error on a size mismatch or a negative radius (naming the junction).
std::vector<Polygon> junction_discs(const std::vector<Junction>& junctions,
                                    const std::vector<double>& radii, int sides = 48);

// The usual radius: half the widest ribbon meeting there plus a margin, both metres.
double junction_disc_radius(const std::vector<double>& member_widths_m, double margin_m);

}  // namespace tw
