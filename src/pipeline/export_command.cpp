#include "pipeline/export_command.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "core/output_guard.hpp"
#include "geo/heightfield.hpp"
#include "pipeline/detail/json_file.hpp"
#include "pipeline/run_layers.hpp"

namespace tw {

namespace fs = std::filesystem;

namespace {

// The heights of `path` over `grid`: the raster itself when it is on the grid, else the DEM read
// with the run's cell size and CRS (read_heightfield's rules, as the pipeline read it), the
// grid a window of it. Throws naming the file when neither holds.
Raster<float> input_heights_on(const fs::path& path, const LayerSet& run, Resampling resampling) {
  const GridSpec& grid = run.grid;
  {
    LayerSet probe;
    const Layer as_is = read_geotiff_layer(path, "height", probe);
    if (probe.grid == grid) return as_is.bands.front();
  }
  HeightfieldOptions options;
  options.resolution = grid.pixel_width;
  options.crs = run.crs_wkt;
  options.resampling = resampling;
  const Heightfield dem = read_heightfield(path.string(), options);
  const double col = (grid.origin_x - dem.grid.origin_x) / dem.grid.pixel_width;
  const double row = (dem.grid.origin_y - grid.origin_y) / dem.grid.pixel_height;
  const int c0 = int(std::lround(col)), r0 = int(std::lround(row));
  if (std::abs(dem.grid.pixel_width - grid.pixel_width) > 1e-9 * grid.pixel_width ||
      std::abs(col - c0) > 1e-6 || std::abs(row - r0) > 1e-6 || c0 < 0 || r0 < 0 ||
      c0 + grid.width > dem.grid.width || r0 + grid.height > dem.grid.height)
    fail(
        "--input-height {}: the run's grid ({} x {} cells of {} m) is not a window of it; give "
        "the DEM the pipeline read or a raster on the run's grid",
        path.string(), grid.width, grid.height, grid.pixel_width);
  Raster<float> out(grid.width, grid.height);
  for (int r = 0; r < grid.height; ++r)
    for (int c = 0; c < grid.width; ++c) out.at(c, r) = dem.height.at(c0 + c, r0 + r);
  return out;
}

}  // namespace

EngineExportResult export_layer_files(const ExportFiles& files,
                                      const std::vector<ExportCurve>& curves,
                                      EngineExportOptions options, int run_tile_size,
                                      const fs::path& dir, OutputStager& stager,
                                      const std::optional<fs::path>& input_height,
                                      Resampling input_resampling) {
  options.tile_size = export_tile_size(options, run_tile_size);
  if (*options.tile_size > 0) return export_tiles_for_engine(files, curves, options, dir, stager);
  LayerSet set;
  set.layers.push_back(read_geotiff_layer(files.height, "height", set));
  if (files.splat) set.layers.push_back(read_geotiff_layer(*files.splat, "splat", set));
  if (!files.crs_wkt.empty()) set.crs_wkt = files.crs_wkt;
  std::optional<Raster<float>> input;
  if (input_height) input = input_heights_on(*input_height, set, input_resampling);
  return export_for_engine(set, curves, options, dir, stager, input ? &*input : nullptr);
}

EngineExportResult run_export_command(const ExportCommand& command) {
  const fs::path& run = command.run_dir;
  if (!fs::exists(run / "report.json"))
    fail("{}: not a finished run (no report.json)", run.string());
  // Read even where nothing below needs it: a corrupt report.json is not a run to export.
  detail::parse_json_file(run / "report.json", "run it again");
  ExportFiles files{required_run_layer_raster(run, "height"), run_layer_raster(run, "splat"), {}};
  int run_tile_size = 0;
  if (is_tiled_run(run)) {
    const nlohmann::json report = detail::parse_json_file(run / "report.json", "run it again");
    if (report.is_object() && report.contains("tiles") && report["tiles"].contains("size") &&
        report["tiles"]["size"].is_number_integer())
      run_tile_size = report["tiles"]["size"].get<int>();
    if (run_tile_size <= 0) fail("{}: report.json gives no tiles.size", run.string());
    if (report.contains("grid") && report["grid"].contains("crs_wkt") &&
        report["grid"]["crs_wkt"].is_string())
      files.crs_wkt = report["grid"]["crs_wkt"].get<std::string>();
  }
  // The DEM read again as the run read it: its `resampling` (report.json's config).
  Resampling input_resampling = Resampling::bilinear;
  if (command.input_height) {
    const nlohmann::json report = detail::parse_json_file(run / "report.json", "run it again");
    if (report.is_object() && report.contains("config") && report["config"].is_object() &&
        report["config"].value("resampling", "") == "cubic")
      input_resampling = Resampling::cubic;
  }
  const std::vector<ExportCurve> curves = fs::exists(run / "features.geojson")
                                              ? read_curves_geojson(run / "features.geojson")
                                              : std::vector<ExportCurve>{};
  require_safe_output(command.out_dir, true,
                      {.command = "export", .option = "--out", .inputs = {run}});
  if (command.verify) verify_run_files(run, "export");
  OutputFolder out(command.out_dir);
  EngineExportOptions options = command.options;
  if (command.input_height) {
    if (!fs::exists(*command.input_height))
      fail("--input-height {}: no such file", command.input_height->string());
    options.layers = true;
  }
  EngineExportResult result =
      export_layer_files(files, curves, options, run_tile_size, command.out_dir, out,
                         command.input_height, input_resampling);
  out.commit();
  return result;
}

}  // namespace tw
