#include "commands/export_command.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "core/output_guard.hpp"
#include "pipeline/export_layer_files.hpp"
#include "pipeline/json_file.hpp"
#include "pipeline/run_layers.hpp"

namespace tw {

namespace fs = std::filesystem;

EngineExportResult run_export_command(const ExportCommand& command) {
  const fs::path& run = command.run_dir;
  if (!fs::exists(run / "report.json"))
    fail("{}: not a finished run (no report.json)", run.string());
  // Read even where nothing below needs it: a corrupt report.json is not a run to export.
  parse_json_file(run / "report.json", "run it again");
  ExportFiles files{required_run_layer_raster(run, "height"), run_layer_raster(run, "splat"), {}};
  int run_tile_size = 0;
  if (is_tiled_run(run)) {
    const nlohmann::json report = parse_json_file(run / "report.json", "run it again");
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
    const nlohmann::json report = parse_json_file(run / "report.json", "run it again");
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
