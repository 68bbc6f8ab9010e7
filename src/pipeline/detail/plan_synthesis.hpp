#pragma once
// A plan's syntheses made apart from plan_world (pipeline/synthesis_job.hpp): what a stored
// plan holds of the placements methods' inputs, and the methods after the one whose syntheses
// were tasks, which plan after all of them.
#include "pipeline/config.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/stages.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/synthesis_method.hpp"

namespace tw::detail {

// The ribbons and synthesis junction discs of the plan (the rest of FeatureRibbons is empty).
FeatureRibbons synthesis_ribbons(const WorldPlan& plan);
ExistingFeatures existing_features(const WorldPlan& plan);

// The method whose placements are made as synthesis tasks (SynthesisMethod::makes_tasks): the
// first of the plan's entries, in method order, whose method makes them. Throws tw::Error when
// none does.
const SynthesisMethod& tasks_method(const WorldPlan& plan);

// What plan_world does after the method `after` when that method's placements were made apart
// (the feature syntheses as tasks, pipeline/synthesis_job.hpp), on a plan read back from its
// folder: every placements method after it that the config gives work reads its inputs again
// (their repairs were the plan's: those warnings are dropped) and plans on the plan's lines,
// ribbons, existing features and heights; then `after` and they are collected, in method order.
// Warnings of their planning and collecting go to `warnings`. Returns each planned method's
// time, as its stage (in method order).
std::vector<StageTiming> plan_after(const PipelineConfig& config, WorldPlan& plan,
                                    const SynthesisMethod& after, Warnings& warnings);

}  // namespace tw::detail
