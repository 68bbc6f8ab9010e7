#pragma once
// Shape-patterns in areas (Olivier et al.) as a synthesis method (pipeline/synthesis_method.hpp):
// every polygon of a `kind: area` class gets the shape-pattern of its sketch
// (detail/areas.hpp), after the curve patterns, whose coverage it avoids.
#include <memory>
#include <string>
#include <vector>

#include "pipeline/detail/areas.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/synthesis_method.hpp"

namespace tw::detail {

struct AreasPlan : MethodPayloadOf<AreasPlan> {
  std::vector<std::string> names;  // of config.areas, in order (PlannedArea::area_class)
  std::vector<PlannedArea> areas;
  // Until collected: the polygons read with the plan's ingest, and what the synthesis returned.
  std::shared_ptr<const std::vector<std::vector<PolygonFeature>>> polygons;
  std::shared_ptr<AreaRun> run;
};

const SynthesisMethod& area_method();

// The plan's areas entry; null when it has none (a plan made by hand).
const AreasPlan* areas_plan(const WorldPlan& plan);
AreasPlan* areas_plan(WorldPlan& plan);

}  // namespace tw::detail
