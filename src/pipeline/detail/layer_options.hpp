#pragma once
// What a run writes besides the pixels, decided once for `terraweave run` and the distributed
// steps (render-tile, finish) so that both write the same bytes: the writers' options with the
// provenance metadata, and the lines as features.geojson and the engines' splines see them.
#include <string>
#include <vector>

#include "geo/features.hpp"
#include "layers/export.hpp"
#include "layers/write.hpp"
#include "pipeline/config.hpp"

namespace tw::detail {

WriteOptions layer_write_options(const PipelineConfig& config, const std::string& heightfield);

// The run's lines as they were built on (clipped, repaired, conformed); a closed ring repeats
// its first point.
std::vector<ExportCurve> export_curves(const PipelineConfig& config,
                                       const std::vector<std::vector<LineFeature>>& lines);

}  // namespace tw::detail
