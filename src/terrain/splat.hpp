#pragma once
// Splat weights: per pixel, how much of each material covers it. Anti-aliased at ribbon
// edges (pixel coverage from the signed distance, a one-pixel linear ramp) and normalized
// so the weights of a pixel sum to 1 in float ("base" takes the rest).
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "terrain/features.hpp"
#include "terrain/height_ops.hpp"

namespace tw {

// The materials, in channel order.
const std::vector<std::string>&
splat_materials();  // base, road, shoulder, riverbed, bank, ridge_rock

struct SplatLayers {
  std::vector<std::string> materials;  // splat_materials()
  std::vector<Raster<float>> weights;  // one per material, each window.width x window.height
};

// Coverage of `window`'s pixels; later kinds of params.precedence cover earlier ones.
SplatLayers compute_splat(const GridSpec& grid, const Window& window,
                          const std::vector<TerrainFeature>& features, const TerrainParams& params);

// The same, with no material painted on nodata: where `height` (the whole grid, or exactly the
// window) is NaN the pixel is all base.
SplatLayers compute_splat(const GridSpec& grid, const Window& window,
                          const std::vector<TerrainFeature>& features, const TerrainParams& params,
                          const Raster<float>& height);

}  // namespace tw
