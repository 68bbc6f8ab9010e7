#pragma once
// The middle stages of a run, between ingest and the layers: ribbons and junctions, the
// features as the terrain module sees them.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "core/warnings.hpp"
#include "geo/features.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/ingest.hpp"
#include "ribbon/junctions.hpp"
#include "ribbon/ribbon.hpp"
#include "terrain/height_ops.hpp"

namespace tw::detail {

// Per class (config order) and feature (reading order).
struct FeatureRibbons {
  std::vector<double> delta;                 // piece length of each class, metres
  std::vector<std::vector<double>> lengths;  // metres, of the feature as read
  std::vector<std::vector<Ribbon>> ribbons;  // no pieces when shorter than delta
  std::vector<Polygon> junction_discs;       // where features meet (output grid's tolerance)
  // The same found with the synthesis canvas's cell as tolerance and margin: independent of
  // the output grid, for the synthesis avoidance.
  std::vector<Polygon> synthesis_junction_discs;
  // Per class and feature: the positions of those junctions it is a member of (the
  // near_junction rules of a mix, synth/exemplar_mix.hpp).
  std::vector<std::vector<std::vector<Vec2>>> synthesis_junctions;
};

// What the ribbons stage reads of each feature class (ribbon_options,
// detail/stage_options.hpp).
struct RibbonClass {
  std::string name;
  double delta = 0.0;  // piece length, metres (class_piece_length, detail/piece_length.hpp)
  bool grown = false;  // `grow:` lines: short ones are counted, not warned about
  std::optional<double> synthesis_width;  // the synthesis ribbon's own width, metres
};
struct RibbonOptions {
  std::vector<RibbonClass> classes;  // config order
  double synthesis_cell = 1.0;       // `synthesis_resolution`: the canvas junctions' tolerance
};

// How the ribbons stage makes one feature's ribbon and finds the junctions at a tolerance: by
// default directly; a run with a cache takes them from it (detail/ribbon_cache.hpp).
struct RibbonSteps {
  std::function<Ribbon(const Curve&, const RibbonParams&)> ribbon = make_ribbon;
  std::function<std::vector<Junction>(const std::vector<Curve>&, double tolerance_m)> junctions =
      [](const std::vector<Curve>& curves, double tolerance_m) {
        return find_junctions(curves, tolerance_m);
      };
};

// Slices every feature into pieces of its class's delta and finds the junctions between all
// features. A feature shorter than one piece gets no pieces and a "shorter_than_delta" warning
// (a grown class's only a count in the log; the run reports them in grow.short_lines).
FeatureRibbons make_feature_ribbons(const RibbonOptions& options,
                                    const std::vector<std::vector<LineFeature>>& lines,
                                    const GridSpec& grid, Warnings& warnings,
                                    const RibbonSteps& steps = {});

// What the terrain stages (conformance, the terrain plan, the earthwork report) read of each
// feature class (terrain_options, detail/stage_options.hpp).
struct TerrainClass {
  std::string name;
  FeatureKind kind = FeatureKind::road;
  RoadProfile road;
  RiverProfile river;
  RidgeProfile ridge;
  double conform_corridor = 0.0;  // `conform.corridor`, metres; 0: as drawn
};
struct TerrainOptions {
  std::vector<TerrainClass> classes;  // config order
};

std::vector<TerrainFeature> terrain_features(const TerrainOptions& options,
                                             const std::vector<std::vector<LineFeature>>& lines);
// Kinds in the order of the classes (a kind's last class decides its place), later wins.
TerrainParams terrain_params(const TerrainOptions& options);

}  // namespace tw::detail
