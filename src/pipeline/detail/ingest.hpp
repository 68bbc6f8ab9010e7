#pragma once
// The ingest stage: the heightfield, the line features of each class and the existing
// (avoidance) features, all in the heightfield's metric grid CRS.
#include <string>
#include <vector>

#include "core/warnings.hpp"
#include "geo/features.hpp"
#include "geo/heightfield.hpp"
#include "geo/heightfield_source.hpp"
#include "pipeline/config.hpp"
#include "raster/polygon.hpp"

namespace tw::detail {

// Opens config.heightfield (at config.resolution) or the world generated from config.generate
// and config.seed, reading no pixel: windows are read as the stages need them.
std::unique_ptr<HeightfieldSource> open_heightfield_source(const PipelineConfig& config,
                                                           Warnings& warnings);

// How open_heightfield_source opens config.heightfield (the plan keeps them: HeightfieldFile).
HeightfieldOptions heightfield_options(const PipelineConfig& config);

// The whole heightfield of open_heightfield_source (an error when every cell is nodata).
Heightfield load_heightfield(const PipelineConfig& config, Warnings& warnings);
// The generator's parameters of a pipeline without a heightfield file.
GeneratedTerrain generated_terrain(const PipelineConfig& config);

// The lines of one class. A class none of whose features lies on the heightfield (an empty
// layer, a where clause matching nothing, or a layer beside the DEM) is a warning
// ("empty_class"), not an error: a pipeline retargeted to another region still runs. Lines are
// clipped to the heightfield plus the halo the later stages reach, then repaired with
// config.repair (read_line_features). Throws geo's per-feature errors, prefixed with the key
// ("features.roads: map.gpkg:roads: FID 2: ...").
std::vector<LineFeature> load_feature_class(const FeatureClassConfig& config,
                                            const Heightfield& heightfield, Warnings& warnings);

struct ExistingFeatures {
  std::vector<Polygon> polygons;
  std::vector<std::vector<Vec2>> lines;
  std::vector<double> line_widths;  // metres, one per line
};

// Entries with a width are read as lines buffered by it (repaired with `repair`), the others as
// polygons (invalid ones made valid). Warnings and errors name `existing.<index>`.
ExistingFeatures load_existing(const std::vector<ExistingConfig>& existing,
                               const Heightfield& heightfield, const LineRepair& repair,
                               Warnings& warnings);

}  // namespace tw::detail
