#include "synth/detail/edge_bound.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "synth/detail/cost.hpp"

namespace tw::detail {

EdgeStats make_edge_stats(const ColumnSet& columns, const std::vector<std::int32_t>& order) {
  const int C = columns.column;
  EdgeStats stats;
  stats.column = C;
  stats.count =
      order.empty() ? int(columns.samples.size() / std::size_t(std::max(C, 1))) : int(order.size());
  stats.words = (C + 63) / 64;
  stats.blocks = (C + kBoundBlock - 1) / kBoundBlock;
  stats.masks.assign(std::size_t(stats.count) * stats.words, 0);
  stats.sums.assign(std::size_t(stats.count) * 3, 0);
  stats.block_sums.assign(std::size_t(stats.count) * stats.blocks * 3, 0.0f);
  for (int j = 0; j < stats.count; ++j) {
    const std::size_t source = order.empty() ? std::size_t(j) : std::size_t(order[j]);
    const std::uint32_t* samples = columns.samples.data() + source * C;
    std::uint64_t* mask = stats.masks.data() + std::size_t(j) * stats.words;
    std::int32_t* sums = stats.sums.data() + std::size_t(j) * 3;
    float* block_sums = stats.block_sums.data() + std::size_t(j) * stats.blocks * 3;
    for (int k = 0; k < C; ++k) {
      if (columns.binary_alpha && is_opaque(samples[k]))
        mask[k / 64] |= std::uint64_t(1) << (k % 64);
      for (int c = 0; c < 3; ++c) {
        sums[c] += std::int32_t(channel_of(samples[k], c));
        block_sums[(k / kBoundBlock) * 3 + c] += float(channel_of(samples[k], c));
      }
    }
  }
  return stats;
}

int mismatched_samples(const EdgeStats& right, int a, const EdgeStats& left, int b) {
  const std::uint64_t* ra = right.masks.data() + std::size_t(a) * right.words;
  const std::uint64_t* lb = left.masks.data() + std::size_t(b) * left.words;
  int m = 0;
  for (int w = 0; w < right.words; ++w) m += std::popcount(ra[w] ^ lb[w]);
  return m;
}

bool whole_edge_bound_exceeds(const EdgeStats& right, int a, const EdgeStats& left, int b, int m,
                              std::int64_t limit) {
  // 16 ||dS|| - C + extra * m > limit  <=>  16 ||dS|| > rhs  <=>  256 ||dS||^2 > rhs^2.
  const std::int64_t rhs = limit + right.column - std::int64_t(kMismatchExtra) * m;
  if (rhs < 0) return true;
  if (rhs >= (std::int64_t(1) << 31)) return false;  // 16 ||dS|| <= 7068 C stays far below
  const std::int32_t* ra = right.sums.data() + std::size_t(a) * 3;
  const std::int32_t* lb = left.sums.data() + std::size_t(b) * 3;
  std::int64_t d2 = 0;
  for (int c = 0; c < 3; ++c) d2 += std::int64_t(ra[c] - lb[c]) * (ra[c] - lb[c]);
  return 256 * d2 > rhs * rhs;
}

float block_colour_bound(const EdgeStats& right, int a, const EdgeStats& left, int b) {
  const float* ra = right.block_sums.data() + std::size_t(a) * right.blocks * 3;
  const float* lb = left.block_sums.data() + std::size_t(b) * left.blocks * 3;
  float bound = 0.0f;
  for (int block = 0; block < right.blocks; ++block) {
    const float dr = ra[3 * block] - lb[3 * block], dg = ra[3 * block + 1] - lb[3 * block + 1];
    const float db = ra[3 * block + 2] - lb[3 * block + 2];
    const float size =
        float(std::min(right.column, (block + 1) * kBoundBlock) - block * kBoundBlock);
    bound += std::max(0.0f, 16.0f * std::sqrt(dr * dr + dg * dg + db * db) - size);
  }
  return bound * (1.0f - 1e-5f) - 1.0f;
}

std::int64_t edge_cost_bound(const EdgeStats& right, int a, const EdgeStats& left, int b,
                             bool binary_alpha) {
  const int m = binary_alpha ? mismatched_samples(right, a, left, b) : 0;
  std::int64_t bound = std::int64_t(kGamma) * m;
  bound = std::max(bound, std::int64_t(std::floor(block_colour_bound(right, a, left, b))));
  // The largest limit the whole-edge test still rejects is a bound too: binary search it.
  std::int64_t lo = bound, hi = std::int64_t(kGamma) * right.column + 1;
  while (lo < hi) {  // invariant: D > lo - 1 is proven
    const std::int64_t mid = lo + (hi - lo + 1) / 2;
    if (whole_edge_bound_exceeds(right, a, left, b, m, mid - 1))
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

__attribute__((target_clones("avx512f", "avx2", "default"), optimize("O3", "no-math-errno")))
std::int64_t
edge_cost_capped(const std::uint32_t* right, const std::uint32_t* left, int count,
                 bool binary_alpha, std::int64_t limit) {
  std::int64_t sum = 0;
  for (int k0 = 0; k0 < count; k0 += kBoundBlock) {
    const int k1 = std::min(count, k0 + kBoundBlock);
    std::int32_t block = 0;
    if (binary_alpha) {
      for (int k = k0; k < k1; ++k) {
        const std::uint32_t p = right[k], q = left[k];
        const std::int32_t dr = std::int32_t(p & 255u) - std::int32_t(q & 255u);
        const std::int32_t dg = std::int32_t((p >> 8) & 255u) - std::int32_t((q >> 8) & 255u);
        const std::int32_t db = std::int32_t((p >> 16) & 255u) - std::int32_t((q >> 16) & 255u);
        const std::int32_t x = 256 * (dr * dr + dg * dg + db * db);
        std::int32_t r = std::int32_t(std::sqrt(float(x)));
        r -= r * r > x ? 1 : 0;
        r += (r + 1) * (r + 1) <= x ? 1 : 0;
        // Opaque = alpha >= 128 = the top bit (kOpaqueAlphaMin == 128).
        block += ((p ^ q) >> 31) ? kGamma : r;
      }
    } else {
      for (int k = k0; k < k1; ++k) block += xi(right[k], left[k], false);
    }
    sum += block;
    if (sum > limit) return sum;
  }
  return sum;
}

static_assert(kOpaqueAlphaMin == 128, "edge_cost_capped reads opacity from the top bit");
static_assert(kMismatchExtra == kGamma - kMaxColourTerm - 1);

}  // namespace tw::detail
