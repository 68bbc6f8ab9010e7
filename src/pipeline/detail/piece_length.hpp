#pragma once
// A class's piece length: the length the ribbons stage cuts its ribbons' pieces at (RibbonClass::
// delta, detail/stage_options.hpp). It is the ribbons' value, not a method's: every class is cut
// into pieces, with synthesis or without, and the patterns method, which synthesizes one pattern
// piece per ribbon piece, reads the same value (its mix gap, its synthesis keys) rather than
// owning it. A method gives it through its ribbon needs (SynthesisMethod::ribbon_needs: the
// patterns' `synthesis.delta`, resolved before any stage by their resolve_defaults).
#include <vector>

#include "pipeline/config.hpp"

namespace tw {
class SynthesisMethod;
}  // namespace tw

namespace tw::detail {

// The methods' piece length (empty `methods`: the built-in ones), else the ribbons' default
// of 4 m.
double class_piece_length(const FeatureClassConfig& feature_class,
                          const std::vector<const SynthesisMethod*>& methods = {});

}  // namespace tw::detail
