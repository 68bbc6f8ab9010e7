#pragma once
// The naive baselines of the quality table (docs/networks.md, "Quality"), exemplar squares (0.4
// of its shorter side) from random places, without any matching, their lines noded by GEOS:
// `placement` (the baseline) drops them at random places until they cover the region
// once on average (overlaps here, gaps there); `tiling` fills a grid of squares over the region,
// one square each (random patch tiling: the exemplar itself but for the seams). What growth must
// beat.
#include <cstdint>
#include <vector>

#include "network/network.hpp"
#include "raster/polygon.hpp"

namespace tw {

enum class BaselineKind { placement, tiling };
Network baseline_network(const Network& exemplar, const std::vector<Polygon>& region,
                         std::uint64_t seed, BaselineKind kind = BaselineKind::placement);

}  // namespace tw
