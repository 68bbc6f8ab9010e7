#pragma once
// Zhou et al. 2013 along ribbons as a synthesis method (pipeline/synthesis_method.hpp): every
// feature of a class with `synthesis` gets its pattern by the exact DP (detail/patterns.hpp);
// the plan keeps each pattern as the renderer needs it and the exemplars they use.
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "pipeline/config.hpp"
#include "pipeline/detail/patterns.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/synthesis_method.hpp"

namespace tw::detail {

struct PatternsPlan : MethodPayloadOf<PatternsPlan> {
  // Synthesized patterns, in synthesis order, and the exemplars they use.
  // An exemplar listed in `unread` (index -> continuous_alpha) is known by its size and channel
  // names only (detail/exemplar_memo.hpp): texels() reads it on first use, once, from any
  // thread (the render of a tile that is rebuilt); a run reusing every tile reads none.
  mutable std::deque<Exemplar> exemplars;
  mutable std::map<std::size_t, bool> unread;
  const Exemplar& texels(std::size_t index) const;
  std::vector<PlannedPattern> patterns;
  // What the synthesis returned, until collected (the areas avoid its coverage).
  std::shared_ptr<PatternRun> run;

 private:
  std::shared_ptr<std::mutex> texels_mutex_ = std::make_shared<std::mutex>();
};

const SynthesisMethod& pattern_method();

// The plan's patterns entry; null when it has none (a plan made by hand).
const PatternsPlan* patterns_plan(const WorldPlan& plan);
PatternsPlan* patterns_plan(WorldPlan& plan);

}  // namespace tw::detail
