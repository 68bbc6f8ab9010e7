#pragma once
// Exact pruning of the DP row (DESIGN.md, "Exact pruning"): cheap statistics of an edge give
// lower bounds on D that never exceed the true integer D, and D itself is evaluated with an
// early exit once it passes the limit a candidate must reach to win.
//
// Per sample, xi(p, q) > 16 ||p - q|| - 1 (it is a floor, or gamma > 16 * 441.7 + 1), and a
// mismatched alpha costs gamma = 16384 >= 16 ||p - q|| - 1 + kMismatchExtra. With m the exact
// number of samples whose (binary) alphas differ, popcount(mask_p ^ mask_q), summing over the
// edge and applying the triangle inequality per block of samples:
//   D >= gamma * m
//   D >= 16 ||sum p - sum q|| - C + kMismatchExtra * m          (whole edge, integer test)
//   D >= sum over blocks b of max(0, 16 ||S_b(p) - S_b(q)|| - n_b)   (float, with a margin)
// With continuous alpha xi >= floor(16 ||p - q||) (gamma exceeds any colour term), so the
// colour bounds hold with m = 0. The bounds only decide what to skip, never a cost, so the
// float rounding of the block bound (lowered by a safety margin) cannot change results.
#include <cstdint>
#include <vector>

#include "synth/detail/stages.hpp"

namespace tw::detail {

inline constexpr int kBoundBlock = 16;                // samples per block of the block bound
inline constexpr std::int32_t kMismatchExtra = 9317;  // gamma - kMaxColourTerm - 1

// Per-position statistics of a set of columns (position-major).
struct EdgeStats {
  int count = 0;                     // positions
  int column = 0;                    // C
  int words = 0;                     // ceil(C / 64): opaque mask words per position
  int blocks = 0;                    // ceil(C / kBoundBlock)
  std::vector<std::uint64_t> masks;  // bit k of word k / 64: sample k is opaque (binary alpha)
  std::vector<std::int32_t> sums;    // R, G, B sums over the whole edge (3 per position)
  std::vector<float> block_sums;     // R, G, B sums per block (3 * blocks per position)
};

// Statistics of the positions `order` of `columns` (all, in order, when `order` is empty).
// Masks are all zero with continuous alpha.
EdgeStats make_edge_stats(const ColumnSet& columns, const std::vector<std::int32_t>& order = {});

// The exact number of samples whose binary alphas differ.
int mismatched_samples(const EdgeStats& right, int a, const EdgeStats& left, int b);

// True when the whole-edge bound proves D(right a, left b) > limit, given m mismatched samples
// (m = 0 with continuous alpha). Exact integer arithmetic.
bool whole_edge_bound_exceeds(const EdgeStats& right, int a, const EdgeStats& left, int b, int m,
                              std::int64_t limit);

// The block colour bound, lowered by the float safety margin (a valid integer bound after
// floor): sum over blocks of max(0, 16 ||dS_b|| - n_b).
float block_colour_bound(const EdgeStats& right, int a, const EdgeStats& left, int b);

// The largest lower bound above (gamma * m, whole edge, blocks), as an integer <= D.
std::int64_t edge_cost_bound(const EdgeStats& right, int a, const EdgeStats& left, int b,
                             bool binary_alpha);

// D(right, left) over `count` samples, exact, with early exit: returns a value > limit as soon
// as a partial sum (every kBoundBlock samples) exceeds it, else the exact D. The colour term is
// floor(sqrt(256 d2)) from one float square root and an exact integer correction, so the loop
// vectorizes; it equals colour_term of cost.hpp for every d2 (tested).
std::int64_t edge_cost_capped(const std::uint32_t* right, const std::uint32_t* left, int count,
                              bool binary_alpha, std::int64_t limit);

}  // namespace tw::detail
