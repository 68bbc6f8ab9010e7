#pragma once
// A plan's syntheses made apart from plan_world (pipeline/synthesis_job.hpp): the inputs of
// synthesize_patterns as a WorldPlan holds them, the steps that put the results into it, and
// the areas, which avoid the curve patterns and so are synthesized after all of them.
#include "pipeline/config.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/stages.hpp"
#include "pipeline/methods/patterns/patterns.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/synthesis_method.hpp"

namespace tw::detail {

// The ribbons and synthesis junction discs of the plan (the rest of FeatureRibbons is empty).
FeatureRibbons synthesis_ribbons(const WorldPlan& plan);
ExistingFeatures existing_features(const WorldPlan& plan);

// The syntheses' reports and cache statuses into plan.report, the patterns as the renderer needs
// them into the plan's patterns entry (methods/patterns/pattern_method.hpp), their exemplars and
// splat materials (the patterns method's collect does the same in plan_world). Throws tw::Error
// naming the class and the channel when an exemplar lacks a mapped channel. A grown class whose
// synthesis dressed none of its lines warns (`grown_undressed`), so that
// --strict fails it.
void add_patterns(const PipelineConfig& config, PatternRun patterns, WorldPlan& plan,
                  Warnings& warnings);

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
