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
// With continuous alpha xi >= floor(16 ||p - q||) (gamma exceeds any colour term), and a
// sample whose alphas fall on either side of 0.5 (a >= 128 > b) has a mismatch weight
// a (255 - b) + (255 - a) b >= 128 * 128 + 127 * 127 = 32513 of 255^2, so the same bounds
// hold with smaller per-mismatch constants (mismatch_cost, mismatch_extra below). The bounds
// only decide what to skip, never a cost, so the float rounding of the block bound (lowered by
// a safety margin) cannot change results.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include "synth/detail/cost.hpp"
#include "synth/detail/stages.hpp"

namespace tw::detail {

inline constexpr int kBoundBlock = 16;                // samples per block of the block bound
inline constexpr std::int32_t kMismatchExtra = 9317;  // gamma - kMaxColourTerm - 1
inline constexpr std::int64_t kMinMismatchWeight = 128 * 128 + 127 * 127;

// The least xi of a mismatched sample: gamma (binary), floor(32513 gamma / 255^2) (continuous).
constexpr std::int64_t mismatch_cost(bool binary_alpha) {
  return binary_alpha ? kGamma : kMinMismatchWeight * kGamma / (255 * 255);
}
// What a mismatched sample adds at least to the colour-term bound 16 ||p - q|| - 1:
// binary gamma - kMaxColourTerm - 1; continuous floor(32513 (gamma - kMaxColourTerm) / 255^2)
// (xi = colour + floor(w_diff (gamma - colour) / 255^2) and the colour term is an integer).
constexpr std::int64_t mismatch_extra(bool binary_alpha) {
  return binary_alpha ? kMismatchExtra
                      : kMinMismatchWeight * (kGamma - kMaxColourTerm) / (255 * 255);
}

// Per-position statistics of a set of columns (position-major).
struct EdgeStats {
  int count = 0;                     // positions
  int column = 0;                    // C
  int words = 0;                     // ceil(C / 64): opaque mask words per position
  int blocks = 0;                    // ceil(C / kBoundBlock)
  bool binary_alpha = true;          // selects the per-mismatch constants
  std::vector<std::uint64_t> masks;  // bit k of word k / 64: sample k is opaque (alpha >= 128)
  std::vector<std::int32_t> sums;    // R, G, B sums over the whole edge (3 per position)
  std::vector<float> block_sums;     // R, G, B sums per block (3 * blocks per position)
};

// Statistics of the positions `order` of `columns` (all, in order, when `order` is empty).
EdgeStats make_edge_stats(const ColumnSet& columns, const std::vector<std::int32_t>& order = {});

// The same statistics in another order: position i of the result is position order[i].
EdgeStats permute_edge_stats(const EdgeStats& stats, const std::vector<std::int32_t>& order);

// The bounds below are inline: they run for every candidate that survives the cost order.

// The number of set bits, without a libgcc call when the target lacks POPCNT.
inline int bit_count(std::uint64_t x) {
#if defined(__POPCNT__)
  return std::popcount(x);
#else
  x = x - ((x >> 1) & 0x5555555555555555ull);
  x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull);
  x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0full;
  return int((x * 0x0101010101010101ull) >> 56);
#endif
}

// The exact number of samples whose alphas fall on different sides of 0.5.
inline int mismatched_samples(const EdgeStats& right, int a, const EdgeStats& left, int b) {
  const std::uint64_t* ra = right.masks.data() + std::size_t(a) * right.words;
  const std::uint64_t* lb = left.masks.data() + std::size_t(b) * left.words;
  int m = 0;
  for (int w = 0; w < right.words; ++w) m += bit_count(ra[w] ^ lb[w]);
  return m;
}

// True when the whole-edge bound proves D(right a, left b) > limit, given m mismatched samples
// (any m not above the true count is sound). Exact integer arithmetic.
inline bool whole_edge_bound_exceeds(const EdgeStats& right, int a, const EdgeStats& left, int b,
                                     int m, std::int64_t limit) {
  // 16 ||dS|| - C + extra * m > limit  <=>  16 ||dS|| > rhs  <=>  256 ||dS||^2 > rhs^2.
  const std::int64_t rhs = limit + right.column - mismatch_extra(right.binary_alpha) * m;
  if (rhs < 0) return true;
  if (rhs >= (std::int64_t(1) << 31)) return false;  // 16 ||dS|| <= 7068 C stays far below
  const std::int32_t* ra = right.sums.data() + std::size_t(a) * 3;
  const std::int32_t* lb = left.sums.data() + std::size_t(b) * 3;
  std::int64_t d2 = 0;
  for (int c = 0; c < 3; ++c) d2 += std::int64_t(ra[c] - lb[c]) * (ra[c] - lb[c]);
  return 256 * d2 > rhs * rhs;
}

// The block colour bound, lowered by the float safety margin (a valid integer bound after
// floor): sum over blocks of max(0, 16 ||dS_b|| - n_b).
inline float block_colour_bound(const EdgeStats& right, int a, const EdgeStats& left, int b) {
  const float* ra = right.block_sums.data() + std::size_t(a) * right.blocks * 3;
  const float* lb = left.block_sums.data() + std::size_t(b) * left.blocks * 3;
  float bound = 0.0f;
  for (int block = 0; block < right.blocks; ++block) {
    const float dr = ra[3 * block] - lb[3 * block], dg = ra[3 * block + 1] - lb[3 * block + 1];
    const float db = ra[3 * block + 2] - lb[3 * block + 2];
    const int size = std::min(right.column, (block + 1) * kBoundBlock) - block * kBoundBlock;
    bound += std::max(0.0f, 16.0f * __builtin_sqrtf(dr * dr + dg * dg + db * db) - float(size));
  }
  return bound * (1.0f - 1e-5f) - 1.0f;
}

// The largest lower bound above (mismatch_cost * m, whole edge, blocks), as an integer <= D.
std::int64_t edge_cost_bound(const EdgeStats& right, int a, const EdgeStats& left, int b,
                             bool binary_alpha);

// D(right, left) over `count` samples, exact, with early exit: returns a value > limit as soon
// as a partial sum (every kBoundBlock samples) exceeds it, else the exact D. The colour term is
// floor(sqrt(256 d2)) from one float square root and an exact integer correction, so the loop
// vectorizes; it equals colour_term of cost.hpp for every d2 (tested).
std::int64_t edge_cost_capped(const std::uint32_t* right, const std::uint32_t* left, int count,
                              bool binary_alpha, std::int64_t limit);

}  // namespace tw::detail
