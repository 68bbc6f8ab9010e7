#pragma once
// A finished run's layer files (height, splat: GeoTIFFs or a tiled run's VRT mosaics) as an
// engine export (layers/export.hpp): what `terraweave export` and a tiled run's `export:` share.
#include <filesystem>
#include <optional>
#include <vector>

#include "geo/heightfield.hpp"
#include "layers/export.hpp"

namespace tw {

// The export of a run's layer files (run tiled at `run_tile_size`, 0: untiled): in tiles read
// by windows when export_tile_size says so, else one heightmap from the layers read whole.
// Shared by the command and by `export:` on tiled runs.
EngineExportResult export_layer_files(
    const ExportFiles& files, const std::vector<ExportCurve>& curves, EngineExportOptions options,
    int run_tile_size, const std::filesystem::path& dir, OutputStager& stager,
    const std::optional<std::filesystem::path>& input_height = std::nullopt,
    Resampling input_resampling = Resampling::bilinear);

}  // namespace tw
