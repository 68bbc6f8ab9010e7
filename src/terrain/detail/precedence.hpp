#pragma once
// Rank of each FeatureKind in TerrainParams::precedence (-1 when absent).
#include <array>

#include "core/error.hpp"
#include "terrain/height_ops.hpp"

namespace tw::detail {

inline std::array<int, 3> precedence_ranks(const TerrainParams& params) {
  std::array<int, 3> ranks{-1, -1, -1};
  for (std::size_t i = 0; i < params.precedence.size(); ++i) {
    int& r = ranks[std::size_t(params.precedence[i])];
    if (r >= 0) fail("terrain precedence names '{}' twice", to_string(params.precedence[i]));
    r = int(i);
  }
  return ranks;
}

}  // namespace tw::detail
