#pragma once
// Named, georeferenced float layers ready to be written: "height" {"height"}, "splat"
// {"splat.base", "splat.road", ...}, "avoidance" {"forbidden", "distance"}.
#include <optional>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "terrain/splat.hpp"

namespace tw {

struct Layer {
  std::string name;                   // file stem: <dir>/<name>.exr
  std::vector<std::string> channels;  // one per band
  std::vector<Raster<float>> bands;   // each grid.width x grid.height
};

struct LayerSet {
  GridSpec grid;
  std::string crs_wkt;
  std::optional<double> nodata;  // written as the GeoTIFF nodata of the "height" layer
  std::vector<Layer> layers;
};

// A layer "height" with one channel "height".
Layer height_layer(Raster<float> height);
// A layer "splat" with channels "splat.<material>".
Layer splat_layer(SplatLayers splat);

// Throws tw::Error naming the layer when channel and band counts differ, a band's size is
// not the grid's, or two layers share a name.
void validate_layer_set(const LayerSet& set);

const Layer* find_layer(const LayerSet& set, const std::string& name);

// Nodata in every layer: each band of every layer but "height" becomes NaN where the height is
// NaN (nodata), as GIS readers expect (docs/pipeline.md, "Nodata"). render_tile calls it on
// every window it renders, so untiled and tiled runs and every writer see the same pixels.
void blank_where_height_is_nodata(LayerSet& set);

}  // namespace tw
