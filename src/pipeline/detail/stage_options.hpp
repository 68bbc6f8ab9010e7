#pragma once
// Each stage's own options, taken from the pipeline config once by the orchestrator (plan_world,
// run_pipeline, the distributed steps): a stage never sees the whole config (DESIGN.md, "A
// stage takes its own options"), so what it depends on is in its signature.
#include <vector>

#include "pipeline/config.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/layer_options.hpp"
#include "pipeline/detail/stages.hpp"

namespace tw {
class SynthesisMethod;
}  // namespace tw

namespace tw::detail {

// `heightfield`, `resolution`, `resampling`, `output.crs`, `generate`, `seed`.
HeightfieldInput heightfield_input(const PipelineConfig& config);

// Per class: what the methods (empty: the built-in ones) need of its ribbons (class_ribbon_needs:
// its piece length or the default, a synthesis ribbon's width, whether short lines are counted);
// and `synthesis_resolution`.
RibbonOptions ribbon_options(const PipelineConfig& config,
                             const std::vector<const SynthesisMethod*>& methods = {});

// Per class: its kind, profiles and `conform.corridor`.
TerrainOptions terrain_options(const PipelineConfig& config);

// `output`'s encodings and provenance (`seed`, the pipeline file), and the classes' names and
// kinds.
LayerOptions layer_options(const PipelineConfig& config);

}  // namespace tw::detail
