#include "layers/layer_set.hpp"

#include <cmath>
#include <limits>
#include <set>

#include "core/error.hpp"

namespace tw {

Layer height_layer(Raster<float> height) {
  Layer layer{"height", {"height"}, {}};
  layer.bands.push_back(std::move(height));
  return layer;
}

Layer splat_layer(SplatLayers splat) {
  Layer layer{"splat", {}, std::move(splat.weights)};
  for (const auto& m : splat.materials) layer.channels.push_back("splat." + m);
  return layer;
}

void validate_layer_set(const LayerSet& set) {
  if (set.grid.width <= 0 || set.grid.height <= 0)
    fail("layer set: empty grid ({} x {})", set.grid.width, set.grid.height);
  std::set<std::string> names;
  for (const auto& layer : set.layers) {
    if (layer.name.empty()) fail("layer set: a layer has no name");
    if (!names.insert(layer.name).second) fail("layer set: two layers are named '{}'", layer.name);
    if (layer.bands.empty()) fail("layer '{}' has no bands", layer.name);
    if (layer.channels.size() != layer.bands.size())
      fail("layer '{}': {} channel names for {} bands", layer.name, layer.channels.size(),
           layer.bands.size());
    std::set<std::string> channels;
    for (std::size_t i = 0; i < layer.bands.size(); ++i) {
      const auto& band = layer.bands[i];
      if (!channels.insert(layer.channels[i]).second)
        fail("layer '{}': channel '{}' appears twice", layer.name, layer.channels[i]);
      if (band.width != set.grid.width || band.height != set.grid.height ||
          band.pixels.size() != std::size_t(band.width) * band.height)
        fail("layer '{}' channel '{}': band is {} x {}, the grid is {} x {}", layer.name,
             layer.channels[i], band.width, band.height, set.grid.width, set.grid.height);
    }
  }
}

const Layer* find_layer(const LayerSet& set, const std::string& name) {
  for (const auto& layer : set.layers)
    if (layer.name == name) return &layer;
  return nullptr;
}

void blank_where_height_is_nodata(LayerSet& set) {
  const Layer* height = find_layer(set, "height");
  if (height == nullptr) return;
  const std::vector<float>& h = height->bands.front().pixels;
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  for (Layer& layer : set.layers) {
    if (&layer == height) continue;
    for (Raster<float>& band : layer.bands) {
      if (band.pixels.size() != h.size())
        fail("layer '{}': band is {} x {}, the height is {} x {}", layer.name, band.width,
             band.height, height->bands.front().width, height->bands.front().height);
      for (std::size_t i = 0; i < h.size(); ++i)
        if (std::isnan(h[i])) band.pixels[i] = kNaN;
    }
  }
}

}  // namespace tw
