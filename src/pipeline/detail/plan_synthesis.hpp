#pragma once
// A plan's syntheses made apart from plan_world (pipeline/synthesis_job.hpp): the inputs of
// synthesize_patterns as a WorldPlan holds them, the steps that put the results into it, and
// the areas, which avoid the curve patterns and so are synthesized after all of them.
#include "pipeline/config.hpp"
#include "pipeline/detail/areas.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/patterns.hpp"
#include "pipeline/detail/stages.hpp"
#include "pipeline/plan.hpp"

namespace tw::detail {

// The ribbons and synthesis junction discs of the plan (the rest of FeatureRibbons is empty).
FeatureRibbons synthesis_ribbons(const WorldPlan& plan);
ExistingFeatures existing_features(const WorldPlan& plan);

// The syntheses' reports and cache statuses into plan.report, the patterns as the renderer needs
// them into the plan's patterns entry (detail/pattern_method.hpp), their exemplars and splat
// materials (the patterns method's collect does the same in plan_world).
// Throws tw::Error naming the class and the channel when an exemplar lacks a mapped channel.
// A grown class whose synthesis dressed none of its lines warns (`grown_undressed`), so that
// --strict fails it.
void add_patterns(const PipelineConfig& config, PatternRun patterns, WorldPlan& plan,
                  Warnings& warnings);

// The areas as the renderer needs them, replacing those the plan's areas entry held: their
// splat materials after the patterns' (call add_patterns first), the output pixels their strokes
// can touch, their report.
void add_areas(const PipelineConfig& config, AreaRun run, WorldPlan& plan);

// The `kind: area` classes synthesized on a plan as plan_world synthesizes them: its lines,
// ribbons, existing features and heights, the polygons read again from their sources, after
// the curve patterns `patterns` (null: none). Warnings are the synthesis's only (the polygons'
// repairs were the plan's).
AreaRun synthesize_plan_areas(const PipelineConfig& config, const WorldPlan& plan,
                              const PatternRun* patterns, Warnings& warnings);

}  // namespace tw::detail
