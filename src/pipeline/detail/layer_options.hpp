#pragma once
// What a run writes besides the pixels, decided once for `terraweave run` and the distributed
// steps (render-tile, finish) so that both write the same bytes: the writers' options with the
// provenance metadata, and the lines as features.geojson and the engines' splines see them.
#include <string>
#include <vector>

#include "geo/features.hpp"
#include "layers/export.hpp"
#include "layers/write.hpp"
#include "terrain/features.hpp"

namespace tw::detail {

// What the layer writers and the line exports read of the pipeline config (layer_options,
// detail/stage_options.hpp).
struct LayerOptions {
  // `output` (formats, exr_half, exr_compression, the GeoTIFF options) with the provenance
  // metadata (version, pipeline file, seed) but the heightfield's name.
  WriteOptions write;
  std::vector<std::string> class_names;  // per feature class, config order
  std::vector<FeatureKind> class_kinds;
};

// The writers' options, the heightfield's name (TERRAWEAVE_HEIGHTFIELD) last in the metadata.
WriteOptions layer_write_options(const LayerOptions& options, const std::string& heightfield);

// The run's lines as they were built on (clipped, repaired, conformed); a closed ring repeats
// its first point.
std::vector<ExportCurve> export_curves(const LayerOptions& options,
                                       const std::vector<std::vector<LineFeature>>& lines);

}  // namespace tw::detail
