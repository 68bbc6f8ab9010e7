#include "pipeline/detail/tile_stats.hpp"

#include <xxhash.h>

namespace tw::detail {

std::uint64_t layer_bytes_hash(const LayerSet& set) {
  XXH64_state_t* state = XXH64_createState();
  XXH64_reset(state, 0);
  for (const Layer& layer : set.layers)
    for (const Raster<float>& band : layer.bands)
      XXH64_update(state, band.pixels.data(), band.pixels.size() * sizeof(float));
  const std::uint64_t hash = XXH64_digest(state);
  XXH64_freeState(state);
  return hash;
}

std::int64_t forbidden_in(const LayerSet& set, const Window& halo, const Window& core) {
  const Layer* avoidance = find_layer(set, "avoidance");
  std::int64_t count = 0;
  for (int row = core.row0; row < core.row_end(); ++row)
    for (int col = core.col0; col < core.col_end(); ++col)
      count += avoidance->bands[0].at(col - halo.col0, row - halo.row0) > 0.0f;
  return count;
}

}  // namespace tw::detail
