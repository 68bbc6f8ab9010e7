#include "pipeline/detail/layer_options.hpp"

#include <filesystem>

namespace tw::detail {

WriteOptions layer_write_options(const LayerOptions& options, const std::string& heightfield) {
  WriteOptions write = options.write;
  write.geotiff_options.metadata.push_back(
      {"TERRAWEAVE_HEIGHTFIELD", std::filesystem::path(heightfield).filename().string()});
  return write;
}

std::vector<ExportCurve> export_curves(const LayerOptions& options,
                                       const std::vector<std::vector<LineFeature>>& lines) {
  std::vector<ExportCurve> curves;
  for (std::size_t c = 0; c < lines.size(); ++c)
    for (const LineFeature& line : lines[c]) {
      ExportCurve& curve = curves.emplace_back();
      curve.feature_class = options.class_names[c];
      curve.kind = std::string(to_string(options.class_kinds[c]));
      curve.fid = line.fid;
      curve.width = line.width;
      curve.points = line.points;
      if (line.closed && !line.points.empty()) curve.points.push_back(line.points.front());
    }
  return curves;
}

}  // namespace tw::detail
