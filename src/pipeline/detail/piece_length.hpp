#pragma once
// A class's piece length: the length the ribbons stage cuts its ribbons' pieces at (RibbonClass::
// delta, detail/stage_options.hpp). It is the ribbons' value, not a method's: every class is cut
// into pieces, with synthesis or without, and the patterns method, which synthesizes one pattern
// piece per ribbon piece, reads the same value (its mix gap, its synthesis keys) rather than
// owning it. Its source is the patterns' `synthesis.delta` (resolved before any stage by their
// resolve_defaults, SynthesisMethod), which the ribbons read as long as `synthesis` is a typed
// field of FeatureClassConfig (docs/methods.md, "Not behind the seam yet").
#include "pipeline/config.hpp"

namespace tw::detail {

// The synthesis delta (resolved: with_method_defaults), else the ribbons' default of 4 m.
double class_piece_length(const FeatureClassConfig& feature_class);

}  // namespace tw::detail
