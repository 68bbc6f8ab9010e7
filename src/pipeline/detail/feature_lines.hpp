#pragma once
// features.geojson: the lines every feature was built on (after repair and conformance), in
// the grid's CRS (report.json grid.crs_wkt), for `terraweave view` and for GIS users.
#include <filesystem>
#include <vector>

#include "geo/features.hpp"
#include "pipeline/config.hpp"

namespace tw::detail {

void write_feature_lines(const PipelineConfig& config,
                         const std::vector<std::vector<LineFeature>>& lines,
                         const std::filesystem::path& path);

}  // namespace tw::detail
