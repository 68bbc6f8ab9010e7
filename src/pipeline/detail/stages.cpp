#include "pipeline/detail/stages.hpp"

#include <algorithm>
#include <cmath>

#include "core/log.hpp"
#include "raster/junction_discs.hpp"

namespace tw::detail {

FeatureRibbons make_feature_ribbons(const RibbonOptions& options,
                                    const std::vector<std::vector<LineFeature>>& lines,
                                    const GridSpec& grid, Warnings& warnings,
                                    const RibbonSteps& steps) {
  FeatureRibbons out;
  std::vector<Curve> curves;
  std::vector<CurveLevel> levels;  // bridges, tunnels and layers meet nothing they pass
  std::vector<double> widths;
  std::vector<double> synthesis_widths;  // the synthesis ribbon's width where it has its own
  for (std::size_t c = 0; c < options.classes.size(); ++c) {
    const RibbonClass& feature_class = options.classes[c];
    const double delta = feature_class.delta;
    out.delta.push_back(delta);
    auto& lengths = out.lengths.emplace_back();
    auto& ribbons = out.ribbons.emplace_back();
    int short_lines = 0;
    for (const LineFeature& line : lines[c]) {
      const Curve curve{line.points, line.closed};
      const double length = arc_length(curve);
      lengths.push_back(length);
      if (length < delta) {
        // Grown lines are short by design (one per spline of an element): counted in the
        // report (grow.short_lines), not a warning each.
        if (!feature_class.grown)
          warnings.add("shorter_than_delta", "features." + feature_class.name, line.fid,
                       fmt::format("{:.2f} m long, shorter than one piece (delta {} m): it gets "
                                   "no ribbon, so no pattern and no avoidance footprint",
                                   length, delta));
        ++short_lines;
        ribbons.push_back({curve, line.width, delta, line.closed, {}});
      } else {
        ribbons.push_back(steps.ribbon(curve, {line.width, delta, 0.0}));
      }
      curves.push_back(curve);
      levels.push_back({line.structure, line.layer});
      widths.push_back(line.width);
      synthesis_widths.push_back(feature_class.synthesis_width
                                     ? std::max(line.width, *feature_class.synthesis_width)
                                     : line.width);
    }
    if (feature_class.grown && short_lines > 0)
      logger().info(
          "features.{}: {} of {} grown lines shorter than one piece (delta {} m): no "
          "ribbon, no pattern",
          feature_class.name, short_lines, lines[c].size(), delta);
  }
  // Meeting points closer than a pixel are one junction; the disc covers the widest member
  // plus a pixel of margin.
  const double pixel = std::max(grid.pixel_width, grid.pixel_height);
  const std::vector<Junction> junctions = at_grade(steps.junctions(curves, pixel), levels);
  std::vector<double> radii;
  for (const Junction& j : junctions) {
    std::vector<double> member_widths;
    for (const JunctionMember& m : j.members) member_widths.push_back(widths[m.curve]);
    radii.push_back(junction_disc_radius(member_widths, pixel));
  }
  out.junction_discs = junction_discs(junctions, radii);
  const double cell = options.synthesis_cell;
  const std::vector<Junction> synthesis_junctions = at_grade(steps.junctions(curves, cell), levels);
  std::vector<double> synthesis_radii;
  for (const Junction& j : synthesis_junctions) {
    std::vector<double> member_widths;
    for (const JunctionMember& m : j.members) member_widths.push_back(synthesis_widths[m.curve]);
    synthesis_radii.push_back(junction_disc_radius(member_widths, cell));
  }
  out.synthesis_junction_discs = junction_discs(synthesis_junctions, synthesis_radii);
  std::vector<std::vector<Vec2>*> junctions_of;  // by curve index
  for (std::size_t c = 0; c < lines.size(); ++c) {
    auto& per_feature = out.synthesis_junctions.emplace_back(lines[c].size());
    for (auto& points : per_feature) junctions_of.push_back(&points);
  }
  for (const Junction& j : synthesis_junctions) {
    for (const JunctionMember& m : j.members) {
      std::vector<Vec2>& points = *junctions_of[m.curve];
      if (points.empty() || points.back() != j.position) points.push_back(j.position);
    }
  }
  logger().info("ribbons: {} features, {} junctions", curves.size(), junctions.size());
  return out;
}

std::vector<TerrainFeature> terrain_features(const TerrainOptions& options,
                                             const std::vector<std::vector<LineFeature>>& lines) {
  std::vector<TerrainFeature> features;
  for (std::size_t c = 0; c < options.classes.size(); ++c) {
    const TerrainClass& feature_class = options.classes[c];
    for (const LineFeature& line : lines[c]) {
      TerrainFeature& f = features.emplace_back();
      f.kind = feature_class.kind;
      f.fid = line.fid;
      f.subject = "features." + feature_class.name;
      f.centerline = Curve{line.points, line.closed};
      f.width = line.width;
      f.structure = line.structure;
      f.layer = line.layer;
      f.road = feature_class.road;
      f.river = feature_class.river;
      f.ridge = feature_class.ridge;
    }
  }
  return features;
}

TerrainParams terrain_params(const TerrainOptions& options) {
  std::vector<FeatureKind> order = {FeatureKind::ridge, FeatureKind::river, FeatureKind::road};
  for (const TerrainClass& feature_class : options.classes) {
    order.erase(std::remove(order.begin(), order.end(), feature_class.kind), order.end());
    order.push_back(feature_class.kind);
  }
  TerrainParams params;
  params.precedence = order;
  return params;
}

}  // namespace tw::detail
