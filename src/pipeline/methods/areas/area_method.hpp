#pragma once
// Shape-patterns in areas (Olivier et al.) as a synthesis method (pipeline/synthesis_method.hpp):
// every polygon of a `kind: area` class gets the shape-pattern of its sketch
// (areas.hpp), after the curve patterns, whose coverage it avoids.
#include <memory>
#include <string>
#include <vector>

#include "geo/features.hpp"
#include "pipeline/detail/method_config.hpp"
#include "pipeline/detail/method_keys.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/synthesis_method.hpp"
#include "sketch/area_synthesis.hpp"

namespace tw::detail {

struct AreaRun;

// One sketch material of an area and where it goes: a splat material and height detail.
struct AreaTarget {
  std::string stroke_material;
  std::size_t material = 0;  // index into WorldPlan::splat_materials
  float height = 0.0f;       // metres times the strokes' coverage
};

// One polygon's shape-pattern as the renderer and the area outputs need it.
struct PlannedArea {
  std::size_t area_class = 0;  // in area_classes(config) / AreasPlan::names
  std::int64_t fid = 0;
  AreaPattern pattern;              // instances and strokes in world metres
  std::vector<AreaTarget> targets;  // every stroke material of the pattern, in config order
  Window window;                    // the output pixels its strokes can touch
};

struct AreasPlan : MethodPayloadOf<AreasPlan> {
  std::vector<std::string> names;  // of area_classes(config), in order (PlannedArea::area_class)
  std::vector<PlannedArea> areas;
  // Until collected: the polygons read with the plan's ingest, and what the synthesis returned.
  std::shared_ptr<const std::vector<std::vector<PolygonFeature>>> polygons;
  std::shared_ptr<AreaRun> run;
};

const SynthesisMethod& area_method();
// Its keys of a pipeline file (detail/method_keys.hpp).
MethodKeys area_keys();
// Its reading of them (detail/method_config.hpp; area_config.cpp).
MethodReader area_reader();

// The plan's areas entry; null when it has none (a plan made by hand).
const AreasPlan* areas_plan(const WorldPlan& plan);
AreasPlan* areas_plan(WorldPlan& plan);

}  // namespace tw::detail
