#pragma once
#include <string>

#include "pipeline/run.hpp"
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

// The lowest and highest height of a band over the tile's core (the band covers `halo`).
HeightRange core_range(const Raster<float>& band, const Window& halo, const Window& core);
// `range` grown to hold `part`.
void widen(HeightRange& range, const HeightRange& part);
// A range as a tile's result keeps it ("" when absent; floats in their shortest exact form).
std::string range_fact(const HeightRange& range);
HeightRange range_of_fact(const std::string& fact);

}  // namespace tw::detail
