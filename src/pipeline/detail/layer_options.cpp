#include "pipeline/detail/layer_options.hpp"

#include <filesystem>

#include "pipeline/version.hpp"

namespace tw::detail {

WriteOptions layer_write_options(const PipelineConfig& config, const std::string& heightfield) {
  WriteOptions options;
  options.exr = config.output.exr;
  options.geotiff = config.output.geotiff;
  options.preview = false;  // the run draws it, with the centerlines on top
  options.exr_pixels = config.output.exr_pixels;
  options.exr_compression = config.output.exr_compression;
  options.geotiff_options = config.output.tiff;
  options.geotiff_options.metadata = {
      {"TERRAWEAVE_VERSION", kTerraweaveVersion},
      {"TERRAWEAVE_PIPELINE", config.file.empty() ? "-" : config.file.filename().string()},
      {"TERRAWEAVE_SEED", std::to_string(config.seed)},
      {"TERRAWEAVE_HEIGHTFIELD", std::filesystem::path(heightfield).filename().string()}};
  return options;
}

std::vector<ExportCurve> export_curves(const PipelineConfig& config,
                                       const std::vector<std::vector<LineFeature>>& lines) {
  std::vector<ExportCurve> curves;
  for (std::size_t c = 0; c < lines.size(); ++c)
    for (const LineFeature& line : lines[c]) {
      ExportCurve& curve = curves.emplace_back();
      curve.feature_class = config.features[c].name;
      curve.kind = std::string(to_string(config.features[c].kind));
      curve.fid = line.fid;
      curve.width = line.width;
      curve.points = line.points;
      if (line.closed && !line.points.empty()) curve.points.push_back(line.points.front());
    }
  return curves;
}

}  // namespace tw::detail
