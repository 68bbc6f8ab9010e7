#pragma once
// The `bind` rules of a class mixing exemplars (choose: mix, docs/pipeline.md): which of its
// lines each rule's where / tags select, asked of OGR on the class's layer (the same attribute
// filters as the class's own selection, never a second SQL evaluator), and the per-feature
// rules that synth/exemplar_mix.hpp's bind_pieces turns into piece constraints.
#include <cstdint>
#include <vector>

#include "geo/features.hpp"
#include "pipeline/config.hpp"
#include "synth/exemplar_mix.hpp"

namespace tw::detail {

// [rule][feature]: 1 where rule's predicate selects lines[feature] (by FID; a rule with neither
// where nor tags selects every line). Throws tw::Error naming the rule's key
// ("features.roads.synthesis.bind.0: ...: bad where clause ...").
std::vector<std::vector<std::uint8_t>> binding_matches(const FeatureClassConfig& feature_class,
                                                       const std::vector<LineFeature>& lines);

// The rules of one feature, in order, for bind_pieces.
std::vector<PieceBinding> feature_bindings(const SynthesisConfig& synthesis,
                                           const std::vector<std::vector<std::uint8_t>>& matches,
                                           std::size_t feature);

}  // namespace tw::detail
