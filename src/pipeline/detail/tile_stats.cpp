#include "pipeline/detail/tile_stats.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "pipeline/detail/manifest.hpp"

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

// The lowest and highest height of a band over the tile's core (the band covers `halo`).
HeightRange core_range(const Raster<float>& band, const Window& halo, const Window& core) {
  Raster<float> inner(core.width, core.height);
  for (int row = 0; row < core.height; ++row)
    for (int col = 0; col < core.width; ++col)
      inner.at(col, row) = band.at(core.col0 - halo.col0 + col, core.row0 - halo.row0 + row);
  return detail::height_range(inner);
}

void widen(HeightRange& range, const HeightRange& part) {
  if (!part) return;
  if (!range) {
    range = part;
    return;
  }
  (*range)[0] = std::min((*range)[0], (*part)[0]);
  (*range)[1] = std::max((*range)[1], (*part)[1]);
}

std::string range_fact(const HeightRange& r) {
  return r ? fmt::format("{} {}", (*r)[0], (*r)[1]) : std::string();
}
HeightRange range_of_fact(const std::string& fact) {
  if (fact.empty()) return std::nullopt;
  const auto space = fact.find(' ');
  return std::array<float, 2>{std::stof(fact.substr(0, space)), std::stof(fact.substr(space + 1))};
}

}  // namespace tw::detail
