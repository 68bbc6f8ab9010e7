#pragma once
// The polygons of an avoidance input that can reach a box, fed to a cache key: the synthesis
// cache (a feature's canvas) and the tile cache (a tile and its halo) select them the same way.
#include <vector>

#include "core/content_hash.hpp"
#include "raster/footprint.hpp"
#include "raster/polygon.hpp"

namespace tw::detail {

// Hashes each polygon whose outer ring's box meets `box` (its ring count, then its rings).
void hash_polygons_meeting(Hasher& h, const std::vector<Polygon>& polygons, const PieceBox& box);

}  // namespace tw::detail
