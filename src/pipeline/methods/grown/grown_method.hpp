#pragma once
// Ornaments grown over the surface (FloralSurf) as a synthesis method
// (pipeline/synthesis_method.hpp): a class with `grow` gets its lines grown
// (grown_classes.hpp); the plan keeps them as ornaments.gpkg holds them.
#include <string>
#include <vector>

#include "ornament/grow.hpp"
#include "pipeline/detail/method_config.hpp"
#include "pipeline/detail/method_keys.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/synthesis_method.hpp"

namespace tw::detail {

// A grown class's lines as ornaments.gpkg holds them (docs/pipeline.md, "Grown classes"); line
// i is the class's feature with FID i + 1.
struct GrownClass {
  std::size_t class_index = 0;  // in config.features / WorldPlan::class_names
  std::string kind;             // hedge, wall, trail, ditch, or the line kind it was given
  double height_m = 0.0;        // the profile's raise (+) or carve (-)
  std::vector<GrownLine> lines;
};

struct GrownPlan : MethodPayloadOf<GrownPlan> {
  std::vector<GrownClass> classes;  // in class order
};

const SynthesisMethod& grown_method();
// Its keys of a pipeline file (detail/method_keys.hpp).
MethodKeys grown_keys();
// Its reading of them (detail/method_config.hpp; grown_config.cpp).
MethodReader grown_reader();

// The plan's grown classes; null when it has no grown entry (a plan made by hand).
const GrownPlan* grown_plan(const WorldPlan& plan);

}  // namespace tw::detail
