#pragma once
// Writing a rendered pattern into the terrain's layers: height detail on top of the heights
// (never on NaN nodata cells) and splat materials that take their share from the others
// proportionally, so the weights keep summing to 1.
#include <cstddef>
#include <vector>

#include "core/grid.hpp"
#include "terrain/splat.hpp"

namespace tw {

// One rendered channel of a pattern and where it goes.
struct PatternLayerTarget {
  const Raster<float>* values = nullptr;  // over the rendered part
  bool to_height = false;                 // else splat material `material`
  std::size_t material = 0;               // index into SplatLayers::materials
  bool is_alpha = false;                  // the share is the coverage itself
};

// Adds a pattern rendered over `part` (coverage and the targets' values, part-sized) into
// `height` and `splat`, which cover `window` (part lies inside it). Targets apply in order;
// height targets add height_detail * value * coverage. Per pixel, so any split of a window
// into parts gives the same bits.
void add_pattern_to_layers(const Window& window, Raster<float>& height, SplatLayers& splat,
                           const Window& part, const Raster<float>& coverage,
                           const std::vector<PatternLayerTarget>& targets, float height_detail);

}  // namespace tw
