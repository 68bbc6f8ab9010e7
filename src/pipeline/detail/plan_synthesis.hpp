#pragma once
// A plan's syntheses made apart from plan_world (pipeline/synthesis_job.hpp): the inputs of
// synthesize_patterns as a WorldPlan holds them, and the step that puts the results into it.
#include "pipeline/config.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/patterns.hpp"
#include "pipeline/detail/stages.hpp"
#include "pipeline/plan.hpp"

namespace tw::detail {

// The ribbons and synthesis junction discs of the plan (the rest of FeatureRibbons is empty).
FeatureRibbons synthesis_ribbons(const WorldPlan& plan);
ExistingFeatures existing_features(const WorldPlan& plan);

// The syntheses' reports and cache statuses into plan.report, the patterns as the renderer needs
// them into plan.patterns, their exemplars and splat materials (plan_world does the same).
// Throws tw::Error naming the class and the channel when an exemplar lacks a mapped channel.
void add_patterns(const PipelineConfig& config, PatternRun patterns, WorldPlan& plan);

}  // namespace tw::detail
