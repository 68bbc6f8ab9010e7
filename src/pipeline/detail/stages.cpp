#include "pipeline/detail/stages.hpp"

#include <algorithm>

#include "core/log.hpp"
#include "raster/junction_discs.hpp"
#include "ribbon/junctions.hpp"

namespace tw::detail {

FeatureRibbons make_feature_ribbons(const PipelineConfig& config,
                                    const std::vector<std::vector<LineFeature>>& lines,
                                    const GridSpec& grid) {
  FeatureRibbons out;
  std::vector<Curve> curves;
  std::vector<double> widths;
  for (std::size_t c = 0; c < config.features.size(); ++c) {
    const FeatureClassConfig& feature_class = config.features[c];
    const double delta =
        feature_class.synthesis ? feature_class.synthesis->delta : SynthesisConfig{}.delta;
    out.delta.push_back(delta);
    auto& lengths = out.lengths.emplace_back();
    auto& ribbons = out.ribbons.emplace_back();
    for (const LineFeature& line : lines[c]) {
      const Curve curve{line.points, line.closed};
      const double length = arc_length(curve);
      lengths.push_back(length);
      if (length < delta) {
        logger().info("features.{}: FID {}: {:.2f} m, shorter than one piece of {} m: no ribbon",
                      feature_class.name, line.fid, length, delta);
        ribbons.push_back({curve, line.width, delta, line.closed, {}});
      } else {
        ribbons.push_back(make_ribbon(curve, {line.width, delta, 0.0}));
      }
      curves.push_back(curve);
      widths.push_back(line.width);
    }
  }
  // Meeting points closer than a pixel are one junction; the disc covers the widest member
  // plus a pixel of margin.
  const double pixel = std::max(grid.pixel_width, grid.pixel_height);
  const std::vector<Junction> junctions = find_junctions(curves, pixel);
  std::vector<double> radii;
  for (const Junction& j : junctions) {
    std::vector<double> member_widths;
    for (const JunctionMember& m : j.members) member_widths.push_back(widths[m.curve]);
    radii.push_back(junction_disc_radius(member_widths, pixel));
  }
  out.junction_discs = junction_discs(junctions, radii);
  logger().info("ribbons: {} features, {} junctions", curves.size(), junctions.size());
  return out;
}

AvoidanceMap build_run_avoidance(const ExistingFeatures& existing, const FeatureRibbons& ribbons,
                                 const GridSpec& grid) {
  AvoidanceInputs inputs;
  inputs.polygons = existing.polygons;
  inputs.lines = existing.lines;
  inputs.line_widths = existing.line_widths;
  for (const auto& class_ribbons : ribbons.ribbons) {
    for (const Ribbon& ribbon : class_ribbons) {
      if (!ribbon.pieces.empty()) inputs.ribbons.push_back(&ribbon);
    }
  }
  inputs.include_foldovers = true;
  inputs.junction_discs = ribbons.junction_discs;
  return build_avoidance_map(inputs, grid, Window::whole(grid));
}

std::vector<TerrainFeature> terrain_features(const PipelineConfig& config,
                                             const std::vector<std::vector<LineFeature>>& lines) {
  std::vector<TerrainFeature> features;
  for (std::size_t c = 0; c < config.features.size(); ++c) {
    const FeatureClassConfig& feature_class = config.features[c];
    for (const LineFeature& line : lines[c]) {
      TerrainFeature& f = features.emplace_back();
      f.kind = feature_class.kind;
      f.fid = line.fid;
      f.centerline = Curve{line.points, line.closed};
      f.width = line.width;
      f.road = feature_class.road;
      f.river = feature_class.river;
      f.ridge = feature_class.ridge;
    }
  }
  return features;
}

TerrainParams terrain_params(const PipelineConfig& config) {
  std::vector<FeatureKind> order = {FeatureKind::ridge, FeatureKind::river, FeatureKind::road};
  for (const FeatureClassConfig& feature_class : config.features) {
    order.erase(std::remove(order.begin(), order.end(), feature_class.kind), order.end());
    order.push_back(feature_class.kind);
  }
  TerrainParams params;
  params.precedence = order;
  return params;
}

}  // namespace tw::detail
