#pragma once
// What the patterns method reports of a run (report.json: a feature's `synthesis` and `cache`,
// `timings.synthesis`, `pattern_violations`, a grown class's `grow.synthesis`; docs/patterns.md):
// its part of the run's report (pipeline/method_report.hpp), which it writes into report.json
// and the plan folder itself.
#include <cstdint>
#include <optional>
#include <vector>

#include "pipeline/cache_status.hpp"
#include "pipeline/detail/plan_codec.hpp"
#include "pipeline/method_report.hpp"
#include "pipeline/run.hpp"
#include "synth/feature_synthesis.hpp"

namespace tw::detail {

// One synthesized feature: its synthesis and whether it was reused from the cache, and why.
struct PatternFeatureReport {
  FeatureSynthesisReport synthesis;
  CacheStatus cache;
};

// A grown class's `synthesis:` over its lines (of those synthesized): `dressed` have a pattern
// on some piece, `no_room` had every piece blocked and are left bare (not an error).
struct GrownSynthesisReport {
  int dressed = 0, no_room = 0;
};

struct PatternsReport : MethodPayloadOf<PatternsReport> {
  // Per class of the run, per feature (the class's report order): the synthesized ones.
  std::vector<std::vector<std::optional<PatternFeatureReport>>> features;
  std::vector<std::optional<GrownSynthesisReport>> grown;  // per class: grown, with synthesis
  std::int64_t violations = 0;  // summed over the features (0, or the run fails)

  // Feature `feature` of class `class_index`'s synthesis; null when it was not synthesized.
  const PatternFeatureReport* feature(std::size_t class_index, std::size_t feature) const {
    if (class_index >= features.size() || feature >= features[class_index].size()) return nullptr;
    const auto& f = features[class_index][feature];
    return f ? &*f : nullptr;
  }
};

// The field list of a feature's synthesis report (pattern_report.cpp): the synthesis cache and
// the synthesis tasks store it too.
TW_PLAN_FIELDS(FeatureSynthesisReport);

// Feature i of class c's synthesis in a run's report; null when it was not synthesized.
inline const FeatureSynthesisReport* synthesis_report(const RunReport& report, std::size_t c,
                                                      std::size_t i) {
  const PatternsReport* part = method_report<PatternsReport>(report);
  const PatternFeatureReport* feature = part ? part->feature(c, i) : nullptr;
  return feature ? &feature->synthesis : nullptr;
}

// Class c's `synthesis:` over its grown lines; null when it is not a grown class with one.
inline const GrownSynthesisReport* grown_synthesis_report(const RunReport& report, std::size_t c) {
  const PatternsReport* part = method_report<PatternsReport>(report);
  return part && c < part->grown.size() && part->grown[c] ? &*part->grown[c] : nullptr;
}

// The opaque pattern pixels on forbidden ones, over every feature (0, or the run fails).
inline std::int64_t pattern_violations(const RunReport& report) {
  const PatternsReport* part = method_report<PatternsReport>(report);
  return part ? part->violations : 0;
}

}  // namespace tw::detail
