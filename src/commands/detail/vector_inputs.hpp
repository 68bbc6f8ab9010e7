#pragma once
// OGR inputs shared by the one-shot commands (`terraweave area`, `terraweave grow`): a source
// string "path[:layer]" and the features to avoid, read once in a frame's CRS.
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <memory>
#include <string>
#include <vector>

#include "core/warnings.hpp"
#include "geo/features.hpp"
#include "geo/heightfield.hpp"
#include "raster/avoidance.hpp"

namespace tw::detail {

// The source's layer (its first when none is named), with the dataset that owns it; throws
// tw::Error naming the path or the layer.
struct OpenLayer {
  std::unique_ptr<GDALDataset> dataset;
  OGRLayer* layer = nullptr;
};
OpenLayer open_layer(const VectorSource& source);

// "path" or "path:layer" (a colon after the first two characters, so "C:/x" stays a path).
VectorSource vector_source(const std::string& source, const std::string& where);

// Whether the source's layer (its first when none is named) holds polygons.
bool is_polygon_layer(const VectorSource& source);

// Polygons as they are; lines buffered to their `width` attribute or OSM tags, else
// default_width metres. `subject` names them in warnings.
AvoidanceInputs avoided_features(const Heightfield& frame, const std::vector<std::string>& avoid,
                                 double default_width, const std::string& subject,
                                 Warnings& warnings);

}  // namespace tw::detail
