#pragma once
// Synthesis width and delta from the exemplar where a class gives none (issue #11, item 2), so
// that the ribbon holds the exemplar's band and the pieces follow its period.
#include "pipeline/config.hpp"

namespace tw::detail {

// The config with every class's synthesis `width` (unless `width: feature`) and `delta` set:
// given values are kept; absent ones come from the exemplars' statistics at the class's scale
// (synth/exemplar_stats.hpp: suggested_width and suggested_delta, texels / scale = metres),
// the widest width and the shortest delta over the class's exemplars, flagged
// width_from_exemplar / delta_from_exemplar. Errors name the class key and the exemplar.
PipelineConfig with_exemplar_defaults(PipelineConfig config);

// A class's piece length: the synthesis delta (resolved), else the ribbons' default of 4 m.
double class_delta(const FeatureClassConfig& feature_class);

}  // namespace tw::detail
