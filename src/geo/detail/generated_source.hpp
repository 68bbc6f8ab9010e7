#pragma once
// What HeightSampler (geo) asks of a source without widening HeightfieldSource's interface.
#include <cstdint>
#include <memory>

#include "geo/heightfield.hpp"
#include "geo/heightfield_source.hpp"

namespace tw::detail {

// Whether `source` is a generated world (open_generated_heightfield), whose every cell is
// computed (fractal noise) rather than read: a HeightSampler then reads small blocks, so the
// plan computes the cells along its features, not the world (issue #23 item 4).
bool is_generated_source(const HeightfieldSource& source);

// The block side a HeightSampler uses over a generated world.
inline constexpr int kGeneratedSampleBlock = 16;

// A generated world's source keeps the last window it computed, so the same window asked again
// (a tile's render, then its report facts) is not computed twice: a window of up to
// `copied_cells` is copied out on every read of it, a larger one moved out on its second read
// (the source then holds nothing). open_generated_heightfield uses kGeneratedCopiedCells.
inline constexpr std::int64_t kGeneratedCopiedCells = std::int64_t(4096) * 4096;  // 64 MiB
std::unique_ptr<HeightfieldSource> open_generated_source(const GeneratedTerrain& params,
                                                         std::int64_t copied_cells);
// The cells a generated source computed (cells_read() counts the kept windows handed out too);
// 0 for another source.
std::int64_t generated_cells(const HeightfieldSource& source);

}  // namespace tw::detail
