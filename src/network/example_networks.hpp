#pragma once
// Synthetic exemplar networks of six kinds (docs/networks.md, "Quality"), generated from a seed:
// the tests, the quality bench and the pictures use the same ones.
#include <cstdint>
#include <string>
#include <vector>

#include "network/exemplar.hpp"

namespace tw {

// "grid" (fields between straight tracks), "bocage" (irregular hedged fields), "drainage"
// (a branching stream tree), "terraces" (walls along contours with ramps), "radial" (rings and
// spokes), "crocodile" (small cells, Y-junctions). About `size_m` metres a side.
NetworkLines example_network(const std::string& kind, double size_m, std::uint64_t seed);
inline constexpr const char* kExampleNetworks[] = {"grid",     "bocage", "drainage",
                                                   "terraces", "radial", "crocodile"};

}  // namespace tw
