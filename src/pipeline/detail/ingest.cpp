#include "pipeline/detail/ingest.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/log.hpp"
#include "pipeline/synthesis_method.hpp"
#include "terrain/features.hpp"

namespace tw::detail {
namespace {

// Metres beyond a feature's half width that the later stages reach (the terrain profile's
// banks or shoulders and falloff, a wider synthesis ribbon) plus one cell: what the clip halo
// must keep so a feature just off the heightfield still shapes its edge.
double clip_margin(const FeatureClassConfig& config, double cell,
                   const std::vector<const SynthesisMethod*>& methods) {
  TerrainFeature profile;
  profile.kind = config.kind;
  profile.road = config.road;
  profile.river = config.river;
  profile.ridge = config.ridge;
  double margin = feature_reach(profile);  // width 0: the reach beyond the half width
  if (const std::optional<double> width = class_ribbon_needs(config, methods).synthesis_width)
    margin = std::max(margin, 0.5 * *width);
  return margin + cell;
}

}  // namespace

std::unique_ptr<HeightfieldSource> open_heightfield_source(const HeightfieldInput& input,
                                                           Warnings& warnings) {
  if (input.file) return open_heightfield(input.file->string(), input.options, warnings);
  return open_generated_heightfield(generated_terrain(input));
}

GeneratedTerrain generated_terrain(const HeightfieldInput& input) {
  const GenerateConfig& g = input.generate;
  if (!input.options.crs.empty() && input.options.crs != g.crs)
    fail("output.crs: a generated world is in generate.crs ({}); set that instead", g.crs);
  GeneratedTerrain params;
  params.width = g.width;
  params.height = g.height;
  params.pixel_size = input.options.resolution.value_or(g.pixel_size);
  params.seed = input.seed;
  params.relief = g.relief;
  params.crs = g.crs;
  params.origin_x = g.origin_x;
  params.origin_y = g.origin_y;
  return params;
}

Heightfield load_heightfield(const HeightfieldInput& input, Warnings& warnings) {
  return read_whole_heightfield(*open_heightfield_source(input, warnings));
}

std::vector<LineFeature> load_feature_class(const FeatureClassConfig& config,
                                            const Heightfield& heightfield, Warnings& warnings,
                                            const LineRepairMemo& repair_memo,
                                            const std::vector<const SynthesisMethod*>& methods) {
  LineClassSpec spec;
  spec.name = config.name;
  spec.subject = "features." + config.name;
  spec.source = {config.source.string(), config.layer, selection_where(config.tags, config.where)};
  spec.width_attribute = config.width_attribute;
  spec.default_width = config.width;
  spec.osm_widths = !config.tags.empty();
  spec.clip_margin = clip_margin(
      config, std::max(heightfield.grid.pixel_width, heightfield.grid.pixel_height), methods);
  spec.repair = config.repair;
  spec.repair_memo = repair_memo;
  std::vector<LineFeature> lines;
  try {
    lines = read_line_features(spec, heightfield, warnings);
  } catch (const Error& e) {
    fail("{}: {}", spec.subject, e.what());  // the key too: file, layer and FID are named
  }
  if (lines.empty()) {
    const std::optional<std::string> why = why_no_features(spec.source, heightfield);
    warnings.add(
        "empty_class", "features." + config.name, std::nullopt,
        fmt::format("{}{}{}: no line feature on the heightfield ({}); the class is left out",
                    config.source.string(), config.layer.empty() ? "" : ":", config.layer,
                    why ? *why : "the layer's extent lies off the heightfield"));
  }
  return lines;
}

ExistingFeatures load_existing(const std::vector<ExistingConfig>& existing,
                               const Heightfield& heightfield, const LineRepair& repair,
                               Warnings& warnings, const LineRepairMemo& repair_memo) {
  ExistingFeatures out;
  for (std::size_t i = 0; i < existing.size(); ++i) {
    const ExistingConfig& e = existing[i];
    const std::string key = "existing." + std::to_string(i);
    const VectorSource source{e.source.string(), e.layer, selection_where(e.tags, e.where)};
    const std::size_t before = out.polygons.size() + out.lines.size();
    try {
      if (e.width > 0.0) {
        LineClassSpec spec;
        spec.name = key;
        spec.source = source;
        spec.default_width = e.width;
        spec.repair = repair;
        spec.repair_memo = repair_memo;
        for (LineFeature& line : read_line_features(spec, heightfield, warnings)) {
          if (line.closed && !line.points.empty()) line.points.push_back(line.points.front());
          out.lines.push_back(std::move(line.points));
          out.line_widths.push_back(e.width);
        }
      } else {
        for (PolygonFeature& polygon : read_polygon_features(source, heightfield, key, warnings)) {
          out.polygons.push_back(std::move(polygon.rings));
        }
      }
      // A source that meets the heightfield and gives nothing is a warning, never a silent 0.
      if (out.polygons.size() + out.lines.size() == before) {
        if (const std::optional<std::string> why = why_no_features(source, heightfield))
          warnings.add("empty_source", key, std::nullopt, *why);
      }
    } catch (const Error& error) {
      fail("{}: {}", key, error.what());
    }
  }
  logger().info("existing: {} polygons, {} lines", out.polygons.size(), out.lines.size());
  return out;
}

}  // namespace tw::detail
