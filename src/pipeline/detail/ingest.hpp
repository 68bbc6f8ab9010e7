#pragma once
// The ingest stage: the heightfield, the line features of each class and the existing
// (avoidance) features, all in the heightfield's metric grid CRS.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/warnings.hpp"
#include "geo/features.hpp"
#include "geo/heightfield.hpp"
#include "geo/heightfield_source.hpp"
#include "pipeline/config.hpp"
#include "raster/polygon.hpp"

namespace tw {
class SynthesisMethod;
}  // namespace tw

namespace tw::detail {

// What the heightfield's ingest reads of the pipeline config (heightfield_input,
// detail/stage_options.hpp): the file and how it is read, or the world to generate.
struct HeightfieldInput {
  std::optional<std::filesystem::path> file;  // `heightfield`; none: the generated world
  // `resolution`, `resampling`, `output.crs`: how the file is read (the plan keeps them:
  // HeightfieldFile); the generated world's cell and CRS check too.
  HeightfieldOptions options;
  GenerateConfig generate;  // `generate`
  std::uint64_t seed = 0;   // `seed`: the generated world's
};

// Opens input.file (at its resolution) or the world generated from input.generate and
// input.seed, reading no pixel: windows are read as the stages need them.
std::unique_ptr<HeightfieldSource> open_heightfield_source(const HeightfieldInput& input,
                                                           Warnings& warnings);

// The whole heightfield of open_heightfield_source (an error when every cell is nodata).
Heightfield load_heightfield(const HeightfieldInput& input, Warnings& warnings);
// The generator's parameters of a pipeline without a heightfield file.
GeneratedTerrain generated_terrain(const HeightfieldInput& input);

// The lines of one class. A class none of whose features lies on the heightfield (an empty
// layer, a where clause matching nothing, or a layer beside the DEM) is a warning
// ("empty_class"), not an error: a pipeline retargeted to another region still runs. Lines are
// clipped to the heightfield plus the halo the later stages reach, then repaired with
// config.repair (read_line_features), through `repair_memo` where set (the run cache's,
// detail/repair_cache.hpp); the halo counts a synthesis ribbon's own width (class_ribbon_needs
// of `methods`, empty: the built-in ones). Throws geo's per-feature errors, prefixed with the key
// ("features.roads: map.gpkg:roads: FID 2: ...").
std::vector<LineFeature> load_feature_class(
    const FeatureClassConfig& config, const Heightfield& heightfield, Warnings& warnings,
    const LineRepairMemo& repair_memo = {},
    const std::vector<const SynthesisMethod*>& methods = {});

struct ExistingFeatures {
  std::vector<Polygon> polygons;
  std::vector<std::vector<Vec2>> lines;
  std::vector<double> line_widths;  // metres, one per line
};

// Entries with a width are read as lines buffered by it (repaired with `repair`), the others as
// polygons (invalid ones made valid). Warnings and errors name `existing.<index>`.
ExistingFeatures load_existing(const std::vector<ExistingConfig>& existing,
                               const Heightfield& heightfield, const LineRepair& repair,
                               Warnings& warnings, const LineRepairMemo& repair_memo = {});

}  // namespace tw::detail
