#pragma once
// What HeightSampler (geo) asks of a source without widening HeightfieldSource's interface.
#include "geo/heightfield_source.hpp"

namespace tw::detail {

// Whether `source` is a generated world (open_generated_heightfield), whose every cell is
// computed (fractal noise) rather than read: a HeightSampler then reads small blocks, so the
// plan computes the cells along its features, not the world (issue #23 item 4).
bool is_generated_source(const HeightfieldSource& source);

// The block side a HeightSampler uses over a generated world.
inline constexpr int kGeneratedSampleBlock = 16;

}  // namespace tw::detail
