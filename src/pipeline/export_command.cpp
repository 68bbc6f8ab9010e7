#include "pipeline/export_command.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "core/output_guard.hpp"
#include "pipeline/run_layers.hpp"

namespace tw {

namespace fs = std::filesystem;

EngineExportResult export_layer_files(const ExportFiles& files,
                                      const std::vector<ExportCurve>& curves,
                                      EngineExportOptions options, int run_tile_size,
                                      const fs::path& dir, OutputStager& stager) {
  options.tile_size = export_tile_size(options, run_tile_size);
  if (*options.tile_size > 0) return export_tiles_for_engine(files, curves, options, dir, stager);
  LayerSet set;
  set.layers.push_back(read_geotiff_layer(files.height, "height", set));
  if (files.splat) set.layers.push_back(read_geotiff_layer(*files.splat, "splat", set));
  if (!files.crs_wkt.empty()) set.crs_wkt = files.crs_wkt;
  return export_for_engine(set, curves, options, dir, stager);
}

EngineExportResult run_export_command(const ExportCommand& command) {
  const fs::path& run = command.run_dir;
  if (!fs::exists(run / "report.json"))
    fail("{}: not a finished run (no report.json)", run.string());
  ExportFiles files{required_run_layer_raster(run, "height"), run_layer_raster(run, "splat"), {}};
  int run_tile_size = 0;
  if (is_tiled_run(run)) {
    const nlohmann::json report = nlohmann::json::parse(std::ifstream(run / "report.json"), nullptr,
                                                        /*allow_exceptions=*/false);
    if (report.is_object() && report.contains("tiles") && report["tiles"].contains("size") &&
        report["tiles"]["size"].is_number_integer())
      run_tile_size = report["tiles"]["size"].get<int>();
    if (run_tile_size <= 0) fail("{}: report.json gives no tiles.size", run.string());
    if (report.contains("grid") && report["grid"].contains("crs_wkt") &&
        report["grid"]["crs_wkt"].is_string())
      files.crs_wkt = report["grid"]["crs_wkt"].get<std::string>();
  }
  const std::vector<ExportCurve> curves = fs::exists(run / "features.geojson")
                                              ? read_curves_geojson(run / "features.geojson")
                                              : std::vector<ExportCurve>{};
  require_safe_output(command.out_dir, true,
                      {.command = "export", .option = "--out", .inputs = {run}});
  if (command.verify) verify_run_files(run, "export");
  OutputFolder out(command.out_dir);
  EngineExportResult result =
      export_layer_files(files, curves, command.options, run_tile_size, command.out_dir, out);
  out.commit();
  return result;
}

}  // namespace tw
