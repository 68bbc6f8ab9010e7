#include "pipeline/detail/feature_lines.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace tw::detail {

void write_feature_lines(const PipelineConfig& config,
                         const std::vector<std::vector<LineFeature>>& lines,
                         const std::filesystem::path& path) {
  nlohmann::json features = nlohmann::json::array();
  for (std::size_t c = 0; c < lines.size(); ++c) {
    for (const LineFeature& line : lines[c]) {
      nlohmann::json coordinates = nlohmann::json::array();
      for (const Vec2& p : line.points) coordinates.push_back({p.x, p.y});
      if (line.closed && !line.points.empty())
        coordinates.push_back({line.points.front().x, line.points.front().y});
      features.push_back({{"type", "Feature"},
                          {"properties",
                           {{"class", config.features[c].name},
                            {"kind", std::string(to_string(config.features[c].kind))},
                            {"fid", line.fid},
                            {"width", line.width}}},
                          {"geometry", {{"type", "LineString"}, {"coordinates", coordinates}}}});
    }
  }
  std::ofstream out(path);
  out << nlohmann::json{{"type", "FeatureCollection"}, {"features", features}}.dump() << '\n';
  out.close();
  if (!out) fail("cannot write {}", path.string());
}

}  // namespace tw::detail
