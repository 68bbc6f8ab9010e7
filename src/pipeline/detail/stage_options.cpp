#include "pipeline/detail/stage_options.hpp"

#include <string>

#include "pipeline/detail/piece_length.hpp"
#include "pipeline/synthesis_method.hpp"
#include "pipeline/version.hpp"

namespace tw::detail {

HeightfieldInput heightfield_input(const PipelineConfig& config) {
  HeightfieldInput input;
  input.file = config.heightfield;
  input.options.resampling = config.resampling;
  input.options.crs = config.output.crs;
  input.options.resolution = config.resolution;  // a region is a window of this grid
  input.generate = config.generate;
  input.seed = config.seed;
  return input;
}

RibbonOptions ribbon_options(const PipelineConfig& config,
                             const std::vector<const SynthesisMethod*>& methods) {
  RibbonOptions options;
  for (const FeatureClassConfig& feature_class : config.features) {
    RibbonClass& c = options.classes.emplace_back();
    c.name = feature_class.name;
    c.delta = class_piece_length(feature_class, methods);
    const RibbonNeeds needs = class_ribbon_needs(feature_class, methods);
    c.grown = needs.counts_short_lines;
    c.synthesis_width = needs.synthesis_width;
  }
  options.synthesis_cell = config.synthesis_resolution;
  return options;
}

TerrainOptions terrain_options(const PipelineConfig& config) {
  TerrainOptions options;
  for (const FeatureClassConfig& feature_class : config.features)
    options.classes.push_back({feature_class.name, feature_class.kind, feature_class.road,
                               feature_class.river, feature_class.ridge,
                               feature_class.conform_corridor});
  return options;
}

LayerOptions layer_options(const PipelineConfig& config) {
  LayerOptions options;
  WriteOptions& write = options.write;
  write.exr = config.output.exr;
  write.geotiff = config.output.geotiff;
  write.preview = false;  // the run draws it, with the centerlines on top
  write.exr_pixels = config.output.exr_pixels;
  write.exr_compression = config.output.exr_compression;
  write.geotiff_options = config.output.tiff;
  write.geotiff_options.metadata = {
      {"TERRAWEAVE_VERSION", kTerraweaveVersion},
      {"TERRAWEAVE_PIPELINE", config.file.empty() ? "-" : config.file.filename().string()},
      {"TERRAWEAVE_SEED", std::to_string(config.seed)}};
  for (const FeatureClassConfig& feature_class : config.features) {
    options.class_names.push_back(feature_class.name);
    options.class_kinds.push_back(feature_class.kind);
  }
  return options;
}

}  // namespace tw::detail
