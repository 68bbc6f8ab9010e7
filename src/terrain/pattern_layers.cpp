#include "terrain/pattern_layers.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace tw {

void add_pattern_to_layers(const Window& window, Raster<float>& height, SplatLayers& splat,
                           const Window& part, const Raster<float>& coverage,
                           const std::vector<PatternLayerTarget>& targets, float height_detail) {
  if (part.col0 < window.col0 || part.row0 < window.row0 || part.col_end() > window.col_end() ||
      part.row_end() > window.row_end())
    fail("add_pattern_to_layers: part ({}, {}, {} x {}) is not inside the window", part.col0,
         part.row0, part.width, part.height);
  const int dc = part.col0 - window.col0, dr = part.row0 - window.row0;
  for (const PatternLayerTarget& t : targets) {
    const Raster<float>& values = *t.values;
    if (t.to_height) {
      for (int row = 0; row < part.height; ++row)
        for (int col = 0; col < part.width; ++col) {
          const float c = coverage.at(col, row);
          float& h = height.at(dc + col, dr + row);
          if (c > 0.0f && !std::isnan(h)) h += height_detail * values.at(col, row) * c;
        }
      continue;
    }
    if (t.material >= splat.weights.size())
      fail("add_pattern_to_layers: splat material {} of {}", t.material, splat.weights.size());
    for (int row = 0; row < part.height; ++row)
      for (int col = 0; col < part.width; ++col) {
        const float c = coverage.at(col, row);
        if (!(c > 0.0f)) continue;
        const float share = std::clamp(t.is_alpha ? c : c * values.at(col, row), 0.0f, 1.0f);
        const int x = dc + col, y = dr + row;
        if (std::isnan(height.at(x, y))) continue;  // nothing is painted on nodata
        for (auto& band : splat.weights) band.at(x, y) *= 1.0f - share;
        splat.weights[t.material].at(x, y) += share;
      }
  }
}

}  // namespace tw
