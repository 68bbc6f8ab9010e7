#include "pipeline/run_layers.hpp"

#include <nlohmann/json.hpp>
#include <string>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "pipeline/json_file.hpp"

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

std::vector<RunFile> hash_run_files(const fs::path& run) {
  const fs::path path = run / "report.json";
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    fail("{}: no report.json: not the output folder of a finished terraweave run", run.string());
  const nlohmann::json report = parse_json_file(path, "run it again");
  if (!report.is_object() || !report.contains("outputs") || !report["outputs"].is_array())
    fail("{}: no `outputs` list (a report of an older terraweave? run it again)", path.string());
  std::vector<RunFile> files;
  for (const nlohmann::json& entry : report["outputs"]) {
    RunFile& file = files.emplace_back();
    try {
      file.name = entry.at("path").get<std::string>();
      file.recorded = {entry.at("bytes").get<std::uintmax_t>(),
                       entry.at("xxh3_128").get<std::string>()};
    } catch (const nlohmann::json::exception& e) {
      fail("{}: outputs: {}", path.string(), e.what());
    }
    const fs::path name = fs::path(file.name).lexically_normal();
    if (name.empty() || name.is_absolute() || *name.begin() == "..")
      fail("{}: outputs: {} is not a path inside the run", path.string(), file.name);
    if (fs::is_regular_file(run / name, ec)) file.now = file_digest(run / name);
  }
  return files;
}

void verify_run_files(const fs::path& run, std::string_view command) {
  for (const RunFile& file : hash_run_files(run)) {
    if (file.matches()) continue;
    const std::string what_to_do = fmt::format(
        "run the pipeline again, or use terraweave {} --no-verify to read the files as they are",
        command);
    if (!file.now)
      fail("{}: {} is missing (report.json names it); {}", run.string(), file.name, what_to_do);
    fail(
        "{}: {} does not match report.json ({} bytes, xxh3_128 {}; the run wrote {} bytes, {}): "
        "it changed after the run; {}",
        run.string(), file.name, file.now->bytes, file.now->xxh3_128, file.recorded.bytes,
        file.recorded.xxh3_128, what_to_do);
  }
}

}  // namespace tw
