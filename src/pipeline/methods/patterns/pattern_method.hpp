#pragma once
// Zhou et al. 2013 along ribbons as a synthesis method (pipeline/synthesis_method.hpp): every
// feature of a class with `synthesis` gets its pattern by the exact DP (patterns.hpp);
// the plan keeps each pattern as the renderer needs it and the exemplars they use.
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/config.hpp"
#include "pipeline/detail/method_config.hpp"
#include "pipeline/detail/method_keys.hpp"
#include "pipeline/methods/patterns/patterns.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/synthesis_method.hpp"

namespace tw::detail {

// Where one exemplar channel of a pattern goes on the output grid.
struct PatternTarget {
  int exemplar_channel = 0;
  bool to_height = false;    // else a splat material
  std::size_t material = 0;  // index into WorldPlan::splat_materials (splat targets)
  bool is_alpha = false;     // the A channel: the share is the coverage itself
};

// One feature's synthesized pattern as the renderer needs it.
struct PlannedPattern {
  std::size_t class_index = 0;     // in config.features / WorldPlan::class_names
  std::size_t feature_index = 0;   // in the class's lines
  std::size_t exemplar_index = 0;  // in PatternsPlan::exemplars
  bool on_ground = true;           // false: a bridge's or tunnel's, written to placements only
  Ribbon ribbon;                   // the synthesis ribbon
  Synthesis synthesis;
  Window window;  // the output pixels its render can touch (empty: off the grid)
  // Render options of its class.
  bool stitch = true;
  double feather = 0.0;
  float height_detail = 1.0f;
  std::vector<PatternTarget> targets;
};

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
// Its keys of a pipeline file (detail/method_keys.hpp).
MethodKeys pattern_keys();
// Its reading of them (detail/method_config.hpp; pattern_config.cpp).
MethodReader pattern_reader();

// A planned pattern as the bytes of its plan object (plan version 10, plan_binary.hpp) and back:
// its fields, then its synthesis as its placements file holds it (synth/placements_io: the
// other values of a Synthesis, its timings and costs of the objective, are not kept). Throws
// tw::Error naming `where` on bytes that are not one pattern.
std::string pattern_to_bytes(const PlannedPattern& pattern);
void pattern_from_bytes(std::string_view bytes, PlannedPattern& pattern, const std::string& where);
// An exemplar (texels and costs) the same way.
std::string exemplar_to_bytes(const Exemplar& exemplar);
void exemplar_from_bytes(std::string_view bytes, Exemplar& exemplar, const std::string& where);

// The plan's patterns entry; null when it has none (a plan made by hand).
const PatternsPlan* patterns_plan(const WorldPlan& plan);
PatternsPlan* patterns_plan(WorldPlan& plan);

// The syntheses' reports and cache statuses into plan.report, the patterns as the renderer needs
// them into the plan's patterns entry, their exemplars and splat materials (the method's
// collect). Throws tw::Error naming the class and the channel when an exemplar lacks a mapped
// channel. A grown class whose synthesis dressed none of its lines warns (`grown_undressed`),
// so that --strict fails it.
void add_patterns(const PipelineConfig& config, PatternRun patterns, WorldPlan& plan,
                  Warnings& warnings);

}  // namespace tw::detail
