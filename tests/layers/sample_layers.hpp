#pragma once
// A small layer set shared by the layer tests: heights, a nodata-free ramp, six splat
// materials in a non-alphabetical order.
#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include <string>

#include "layers/layer_set.hpp"

namespace tw::test {

inline std::string utm31n_wkt() {
  OGRSpatialReference srs;
  srs.importFromEPSG(32631);
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  std::string out(wkt);
  CPLFree(wkt);
  return out;
}

// A w x h world (10 m cells) in UTM 31N: heights 100 + col + row / 3, six splat materials
// whose weights say their band index (material m is 1 where col % 6 == m).
inline LayerSet interop_set(int w = 40, int h = 30) {
  LayerSet set;
  set.grid = GridSpec{w, h, 500000.0, 5000000.0 + 10.0 * h, 10.0, 10.0};
  set.crs_wkt = utm31n_wkt();
  Raster<float> height(w, h);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) height.at(c, r) = 100.0f + float(c) + float(r) / 3.0f;
  set.layers.push_back(height_layer(std::move(height)));
  SplatLayers splat;
  splat.materials = {"base", "road", "shoulder", "riverbed", "bank", "crest"};  // not sorted
  for (int m = 0; m < 6; ++m) {
    Raster<float> weight(w, h, 0.0f);
    for (int r = 0; r < h; ++r)
      for (int c = m; c < w; c += 6) weight.at(c, r) = 1.0f;
    splat.weights.push_back(std::move(weight));
  }
  set.layers.push_back(splat_layer(std::move(splat)));
  return set;
}

}  // namespace tw::test
