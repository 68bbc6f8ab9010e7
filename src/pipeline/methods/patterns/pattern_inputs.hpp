#pragma once
// What the patterns method makes of its inputs, the exemplars, before any stage starts
// (SynthesisMethod::check_input and resolve_defaults): each exemplar checked, and the synthesis
// width and delta from the exemplars where a class gives none (issue #11, item 2), so that the
// ribbon holds the exemplar's band and the pieces follow its period.
#include "pipeline/config.hpp"
#include "pipeline/detail/input_check.hpp"

namespace tw::detail {

// Every class's synthesis `width` (unless `width: feature`) and `delta` set: given values are
// kept; absent ones come from the exemplars' statistics at the class's scale
// (synth/exemplar_stats.hpp: suggested_width and suggested_delta, texels / scale = metres), the
// widest width and the shortest delta over the class's exemplars, flagged width_from_exemplar /
// delta_from_exemplar. Errors name the class key and the exemplar.
void resolve_exemplar_defaults(PipelineConfig& config);

// Checks an exemplar input (a method input of role kExemplarRole; false for any other): the image
// read whole, with its NAME_height.tif twin when present; throws tw::Error "<named_at>: cannot be
// used as an exemplar: <why>". With a run cache, an exemplar whose bytes were validated before is
// not read again, and one validated now is remembered there (detail/exemplar_memo.hpp; a failed
// write only means it is read again next time).
bool check_exemplar_input(const InputFile& input, InputCheck& check);

}  // namespace tw::detail
