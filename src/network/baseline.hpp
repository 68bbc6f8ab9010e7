#pragma once
// The naive baseline of the quality table (docs/networks.md, "Quality"): square patches of the
// exemplar dropped at random places over the region, without any matching, until they cover it
// once on average; where they overlap their lines are noded into junctions (GEOS), then cut by
// the region. What growth must beat.
#include <cstdint>
#include <vector>

#include "network/network.hpp"
#include "raster/polygon.hpp"

namespace tw {

Network baseline_network(const Network& exemplar, const std::vector<Polygon>& region,
                         std::uint64_t seed);

}  // namespace tw
