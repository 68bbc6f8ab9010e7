#pragma once
// Ornaments grown over the surface (FloralSurf) as a synthesis method
// (pipeline/synthesis_method.hpp): a class with `grow` gets its lines grown
// (detail/grown_classes.hpp); the plan keeps them as ornaments.gpkg holds them.
#include <vector>

#include "pipeline/plan.hpp"
#include "pipeline/synthesis_method.hpp"

namespace tw::detail {

struct GrownPlan : MethodPayloadOf<GrownPlan> {
  std::vector<GrownClass> classes;  // in class order
};

const SynthesisMethod& grown_method();

// The plan's grown classes; null when it has no grown entry (a plan made by hand).
const GrownPlan* grown_plan(const WorldPlan& plan);

}  // namespace tw::detail
