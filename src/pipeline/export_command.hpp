#pragma once
// `terraweave export RUN_DIR --to ENGINE --out DIR`: a finished run's height.tif, splat.tif
// and features.geojson as an engine export (layers/export.hpp), written atomically into DIR.
#include <filesystem>

#include "layers/export.hpp"

namespace tw {

struct ExportCommand {
  std::filesystem::path run_dir;
  std::filesystem::path out_dir;
  EngineExportOptions options;
};

// Throws tw::Error naming the missing or unreadable file of the run.
EngineExportResult run_export_command(const ExportCommand& command);

}  // namespace tw
