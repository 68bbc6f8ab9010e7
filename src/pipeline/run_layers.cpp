#include "pipeline/run_layers.hpp"

#include <string>

#include "core/error.hpp"

namespace tw {

namespace fs = std::filesystem;

namespace {

// The files a layer may be in, in the order they are read: the tiled run's mosaic; an untiled
// run's GeoTIFF twin (float32, as written), else its EXR (the only file of `formats: [exr]`).
std::vector<fs::path> layer_paths(const fs::path& run, std::string_view layer) {
  const std::string stem(layer);
  if (is_tiled_run(run)) return {run / (stem + ".vrt")};
  return {run / (stem + ".tif"), run / (stem + ".exr")};
}

}  // namespace

bool is_tiled_run(const fs::path& run) {
  std::error_code ec;
  return fs::is_regular_file(run / "height.vrt", ec);
}

std::optional<fs::path> run_layer_raster(const fs::path& run, std::string_view layer) {
  for (const fs::path& path : layer_paths(run, layer)) {
    std::error_code ec;
    if (fs::is_regular_file(path, ec)) return path;
  }
  return std::nullopt;
}

fs::path required_run_layer_raster(const fs::path& run, std::string_view layer) {
  if (std::optional<fs::path> path = run_layer_raster(run, layer)) return *path;
  const std::vector<fs::path> paths = layer_paths(run, layer);
  if (paths.size() == 1)
    fail("{}: the run wrote no {}", run.string(), paths.front().filename().string());
  // Also a tiled run without GeoTIFF twins: it has no mosaics (they are VRTs over the twins).
  fail(
      "{}: the run wrote no {} or {} (a tiled run is read through the GeoTIFF mosaics its "
      "output.formats [exr, geotiff] writes)",
      run.string(), paths[0].filename().string(), paths[1].filename().string());
}

}  // namespace tw
