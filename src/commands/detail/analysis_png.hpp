#pragma once
// A picture of the Support Structure Hierarchy of one sketch (docs/shape-patterns.md), five
// panels left to right: strokes; shapes (oriented boxes, with their central point or support
// segment); fibres with their ribbons; fibre medians with their displacement areas; lead
// directions with the gaps between their medians.
#include <filesystem>

#include "sketch/hierarchy.hpp"

namespace tw::detail {

// Panels of `panel` pixels square, one per level, on white; a colour per member.
void write_analysis_png(const std::filesystem::path& path, const SupportHierarchy& hierarchy,
                        int panel = 360);

}  // namespace tw::detail
