#pragma once
// Reading the patterns' keys of a pipeline file (docs/patterns.md, docs/pipeline.md): a line
// class's `synthesis:` block, and `synthesis_resolution` and `synthesis_order` at the top level.
#include "pipeline/detail/method_config.hpp"

namespace tw::detail {

// A line class's `synthesis:` block, if there (MethodReader::read_class). Throws tw::Error
// naming the file, line and key of the first bad value; the exemplars go to `inputs`.
void read_pattern_class(ClassReading& r);

// `synthesis_resolution`, and `synthesis_order`: each class with synthesis exactly once
// (default: precedence order). MethodReader::read_root.
void read_pattern_root(RootReading& r);

}  // namespace tw::detail
