#pragma once
// Height operations: carve rivers, grade roads, raise ridges on a heightfield.
#include <functional>
#include <vector>

#include "core/grid.hpp"
#include "core/warnings.hpp"
#include "geo/height_sampler.hpp"
#include "geo/heightfield.hpp"
#include "terrain/features.hpp"

namespace tw {

struct TerrainParams {
  // Kinds in the order they are applied; a later kind overwrites earlier ones where its
  // influence weight is 1 and blends by weight elsewhere.
  std::vector<FeatureKind> precedence = {FeatureKind::ridge, FeatureKind::river, FeatureKind::road};
};

// Where a bound on the earthwork (a river's max_carve, a road's max_cut or max_fill) held a
// feature's centreline profile: over how many metres, and its worst point.
struct ProfileLimit {
  double length = 0.0;  // metres of centreline; 0: the bound never held
  double excess = 0.0;  // metres beyond the bound the unbounded profile went, at worst
  double along = 0.0;   // arc length of the worst point
  Vec2 at{};            // world position of the worst point
};

// One feature's earthwork along its centreline, after the bounds: the largest cut (profile
// below the terrain: a river bed, a road cutting) and fill (above: a road embankment, a ridge).
struct FeatureEarthwork {
  double max_cut = 0.0;
  double max_fill = 0.0;
  ProfileLimit cut_limited;   // rivers: max_carve; roads: max_cut
  ProfileLimit fill_limited;  // roads: max_fill
};

// The longitudinal profiles of every feature, sampled from the terrain before any change.
// Computing them once for the whole grid and applying them window by window keeps tiles
// seamless (a tile never sees its neighbours' edits).
struct TerrainPlan {
  std::vector<TerrainFeature> features;  // validated copies, grouped by precedence
  // One per feature: its profile every `step` metres of arc length (road surface height,
  // river bed = water surface - depth, unused for ridges; a bridge's or tunnel's deck) and
  // the step.
  std::vector<std::vector<float>> profiles;
  std::vector<double> steps;
  // One per feature: its index in the features given to plan_terrain, and its earthwork.
  std::vector<std::size_t> input_index;
  std::vector<FeatureEarthwork> earthwork;
  TerrainParams params;
};

// Samples and grades the profiles (junctions included, see docs/terrain.md), reading heights
// through `heights` (the cells along the features, never the whole grid); NaN cells are never
// read as heights. A feature on the grid but only over nodata is left out with an
// `over_nodata` warning (its subject, FID).
TerrainPlan plan_terrain(HeightSampler& heights, const std::vector<TerrainFeature>& features,
                         const TerrainParams& params, Warnings& warnings);
// What plan_terrain reads of the heightfield: the heights under a centreline every `step`
// metres, nodata gaps bridged (detail::terrain_along; empty when all of it is over nodata).
// A caller may keep them per centreline and give back those of unchanged features (the run
// cache: a moved road samples only itself again).
using HeightsAlong = std::function<std::vector<double>(const Curve& centerline, double step)>;
// The HeightsAlong of `heights` (which must outlive it).
HeightsAlong sample_heights_along(HeightSampler& heights);
// The same plan, reading the heights through `heights_along` (over `grid`).
TerrainPlan plan_terrain(const GridSpec& grid, const HeightsAlong& heights_along,
                         const std::vector<TerrainFeature>& features, const TerrainParams& params,
                         Warnings& warnings);
// The same over `height`, which covers the whole grid (the same plan, bit for bit).
TerrainPlan plan_terrain(const Raster<float>& height, const GridSpec& grid,
                         const std::vector<TerrainFeature>& features, const TerrainParams& params,
                         Warnings& warnings);
// The same, its warnings only logged.
TerrainPlan plan_terrain(const Raster<float>& height, const GridSpec& grid,
                         const std::vector<TerrainFeature>& features, const TerrainParams& params);

// Applies a plan to the pixels of `window` of `height`, which covers the whole grid or exactly
// the window (a tile: the same bits as the window of a whole-grid call).
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
