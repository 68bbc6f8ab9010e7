#pragma once
// Height operations: carve rivers, grade roads, raise ridges on a heightfield.
#include <vector>

#include "core/grid.hpp"
#include "core/warnings.hpp"
#include "geo/heightfield.hpp"
#include "terrain/features.hpp"

namespace tw {

struct TerrainParams {
  // Kinds in the order they are applied; a later kind overwrites earlier ones where its
  // influence weight is 1 and blends by weight elsewhere.
  std::vector<FeatureKind> precedence = {FeatureKind::ridge, FeatureKind::river, FeatureKind::road};
};

// The longitudinal profiles of every feature, sampled from the terrain before any change.
// Computing them once for the whole grid and applying them window by window keeps tiles
// seamless (a tile never sees its neighbours' edits).
struct TerrainPlan {
  std::vector<TerrainFeature> features;  // validated copies, grouped by precedence
  // One per feature: its profile every `step` metres of arc length (road surface height,
  // river bed = water surface - depth, unused for ridges) and the step.
  std::vector<std::vector<float>> profiles;
  std::vector<double> steps;
  TerrainParams params;
};

// Samples and grades the profiles (junctions included, see docs/terrain.md). `height`
// covers the whole grid; NaN cells are never read as heights. A feature on the grid but only
// over nodata is left out with an `over_nodata` warning (its subject, FID).
TerrainPlan plan_terrain(const Raster<float>& height, const GridSpec& grid,
                         const std::vector<TerrainFeature>& features, const TerrainParams& params,
                         Warnings& warnings);
// The same, its warnings only logged.
TerrainPlan plan_terrain(const Raster<float>& height, const GridSpec& grid,
                         const std::vector<TerrainFeature>& features, const TerrainParams& params);

// Applies a plan to the pixels of `window` of `height` (which covers the whole grid).
// NaN cells are never read or written. Parallel over tiles, bit-identical for any thread count.
void apply_terrain(Raster<float>& height, const GridSpec& grid, const Window& window,
                   const TerrainPlan& plan);

// plan_terrain + apply_terrain.
void shape_terrain(Raster<float>& height, const GridSpec& grid, const Window& window,
                   const std::vector<TerrainFeature>& features, const TerrainParams& params,
                   Warnings& warnings);
void shape_terrain(Raster<float>& height, const GridSpec& grid, const Window& window,
                   const std::vector<TerrainFeature>& features, const TerrainParams& params);

// The whole heightfield (its grid, its NaN nodata).
void shape_heightfield(Heightfield& heightfield, const std::vector<TerrainFeature>& features,
                       const TerrainParams& params = {});

}  // namespace tw
