#pragma once
// Zhou et al. 2013 along ribbons as a synthesis method (pipeline/synthesis_method.hpp): every
// feature of a class with `synthesis` gets its pattern by the exact DP (detail/patterns.hpp);
// the plan keeps each pattern as the renderer needs it and the exemplars they use.
#include <deque>
#include <memory>
#include <vector>

#include "pipeline/config.hpp"
#include "pipeline/detail/patterns.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/synthesis_method.hpp"

namespace tw::detail {

struct PatternsPlan : MethodPayloadOf<PatternsPlan> {
  // Synthesized patterns, in synthesis order, and the exemplars they use.
  std::deque<Exemplar> exemplars;
  std::vector<PlannedPattern> patterns;
  // What the synthesis returned, until collected (the areas avoid its coverage).
  std::shared_ptr<PatternRun> run;
};

const SynthesisMethod& pattern_method();

// The plan's patterns entry; null when it has none (a plan made by hand).
const PatternsPlan* patterns_plan(const WorldPlan& plan);
PatternsPlan* patterns_plan(WorldPlan& plan);

}  // namespace tw::detail
