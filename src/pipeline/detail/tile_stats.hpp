#pragma once
// What report.json says about one rendered tile, computed where it is rendered (run_pipeline's
// loop, or terraweave render-tile in another process).
#include <cstdint>

#include "core/grid.hpp"
#include "layers/layer_set.hpp"

namespace tw::detail {

// xxHash64 of every band's pixels, layer after layer (report.json `tiles`).
std::uint64_t layer_bytes_hash(const LayerSet& set);

// Forbidden pixels of the avoidance layer in `core` (set covers `halo`).
std::int64_t forbidden_in(const LayerSet& set, const Window& halo, const Window& core);

}  // namespace tw::detail
