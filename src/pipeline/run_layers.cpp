#include "pipeline/run_layers.hpp"

#include <string>

#include "core/error.hpp"

namespace tw {

namespace fs = std::filesystem;

namespace {

fs::path layer_path(const fs::path& run, std::string_view layer) {
  return run / (std::string(layer) + (is_tiled_run(run) ? ".vrt" : ".tif"));
}

}  // namespace

bool is_tiled_run(const fs::path& run) {
  std::error_code ec;
  return fs::is_regular_file(run / "height.vrt", ec);
}

std::optional<fs::path> run_layer_raster(const fs::path& run, std::string_view layer) {
  fs::path path = layer_path(run, layer);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  return path;
}

fs::path required_run_layer_raster(const fs::path& run, std::string_view layer) {
  if (std::optional<fs::path> path = run_layer_raster(run, layer)) return *path;
  fail("{}: the run wrote no {} (output.geotiff: false?)", run.string(),
       layer_path(run, layer).filename().string());
}

}  // namespace tw
