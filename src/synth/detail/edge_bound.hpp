#pragma once
// Exact pruning of the DP row (DESIGN.md, "Exact pruning"): cheap per-block statistics of an
// edge give a lower bound on D that never exceeds the true integer D.
//
// Per sample, xi(p, q) > 16 ||p - q|| - 1 (it is a floor, or gamma > 16 * 441.7 + 1), and a
// mismatched alpha costs gamma = 16384 >= 16 ||p - q|| - 1 + 9317. Summing over a block of n
// samples and applying the triangle inequality:
//   D_block >= 16 ||sum p - sum q|| - n + 9317 m  >= 16 ||Delta S|| - n + 9317 |Delta opaque|
//   D_block >= gamma * m >= gamma * |Delta opaque|   (m = mismatched samples >= |Delta opaque|)
// (binary alpha). With continuous alpha xi >= floor(16 ||p - q||), so the colour term alone
// holds. The bound is evaluated in float with a safety margin; it only decides what to skip,
// never a cost, so its rounding cannot change results.
#include <cstdint>
#include <vector>

#include "synth/detail/stages.hpp"

namespace tw::detail {

inline constexpr int kBoundBlock = 16;  // samples per block
inline constexpr float kMismatchExtra = 9317.0f;

// Block statistics of a set of columns, block-major (stats[b * count + j]) so the bound over
// many positions is a vectorizable loop.
struct EdgeStats {
  int count = 0;   // positions
  int blocks = 0;  // ceil(C / kBoundBlock)
  std::vector<float> opaque, red, green, blue;
  std::vector<float> block_size;  // samples in block b
};

// Statistics of the positions `order` of `columns` (all, in order, when `order` is empty).
EdgeStats make_edge_stats(const ColumnSet& columns, const std::vector<std::int32_t>& order = {});

// The lower bound on D for position a of `right` against position b of `left`, already
// lowered by the float safety margin (so it is a valid integer bound after floor).
float edge_cost_bound(const EdgeStats& right, int a, const EdgeStats& left, int b,
                      bool binary_alpha);

}  // namespace tw::detail
