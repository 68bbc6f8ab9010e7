#include "pipeline/export_command.hpp"

#include "core/error.hpp"
#include "core/output_folder.hpp"

namespace tw {

namespace fs = std::filesystem;

EngineExportResult run_export_command(const ExportCommand& command) {
  const fs::path& run = command.run_dir;
  if (!fs::exists(run / "report.json"))
    fail("{}: not a finished run (no report.json)", run.string());
  if (!fs::exists(run / "height.tif"))
    fail("{}: the run wrote no height.tif (output.geotiff: false?)", run.string());
  LayerSet set;
  set.layers.push_back(read_geotiff_layer(run / "height.tif", "height", set));
  if (fs::exists(run / "splat.tif"))
    set.layers.push_back(read_geotiff_layer(run / "splat.tif", "splat", set));
  const std::vector<ExportCurve> curves = fs::exists(run / "features.geojson")
                                              ? read_curves_geojson(run / "features.geojson")
                                              : std::vector<ExportCurve>{};
  OutputFolder out(command.out_dir);
  EngineExportResult result = export_for_engine(set, curves, command.options, command.out_dir, out);
  out.commit();
  return result;
}

}  // namespace tw
