#pragma once
// `terraweave export RUN_DIR --to ENGINE --out DIR`: a finished run's height and splat layers
// (GeoTIFFs, or a tiled run's VRT mosaics) and features.geojson as an engine export
// (layers/export.hpp), written atomically into DIR.
#include <filesystem>
#include <optional>

#include "geo/heightfield.hpp"
#include "layers/export.hpp"

namespace tw {

struct ExportCommand {
  std::filesystem::path run_dir;
  std::filesystem::path out_dir;
  EngineExportOptions options;
  // The heights before the run, for the non-destructive layers (options.layers): a raster on
  // the run's grid, or the DEM the pipeline read (read again with the run's cell size, CRS and
  // resampling, the run's grid a window of it).
  std::optional<std::filesystem::path> input_height;
  // Check the run's files against report.json first (--no-verify: false).
  bool verify = true;
};

// Throws tw::Error naming the missing or unreadable file of the run, or (verify) the file that
// no longer matches report.json (pipeline/run_layers.hpp, verify_run_files).
EngineExportResult run_export_command(const ExportCommand& command);

}  // namespace tw
