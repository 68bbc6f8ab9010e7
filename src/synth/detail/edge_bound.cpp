#include "synth/detail/edge_bound.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
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
  tbb::parallel_for(tbb::blocked_range<int>(0, stats.count, 256), [&](auto range) {
    for (int j = range.begin(); j < range.end(); ++j) {
      const std::size_t source = order.empty() ? std::size_t(j) : std::size_t(order[j]);
      const std::uint32_t* samples = columns.samples.data() + source * C;
      std::uint64_t* mask = stats.masks.data() + std::size_t(j) * stats.words;
      std::int32_t* sums = stats.sums.data() + std::size_t(j) * 3;
      float* block_sums = stats.block_sums.data() + std::size_t(j) * stats.blocks * 3;
      for (int b = 0; b < stats.blocks; ++b) {
        std::int32_t red = 0, green = 0, blue = 0;
        for (int k = b * kBoundBlock; k < std::min(C, (b + 1) * kBoundBlock); ++k) {
          const std::uint32_t t = samples[k];
          if (columns.binary_alpha && is_opaque(t)) mask[k / 64] |= std::uint64_t(1) << (k % 64);
          red += std::int32_t(t & 255u);
          green += std::int32_t((t >> 8) & 255u);
          blue += std::int32_t((t >> 16) & 255u);
        }
        block_sums[3 * b] = float(red);
        block_sums[3 * b + 1] = float(green);
        block_sums[3 * b + 2] = float(blue);
        sums[0] += red;
        sums[1] += green;
        sums[2] += blue;
      }
    }
  });
  return stats;
}

EdgeStats permute_edge_stats(const EdgeStats& stats, const std::vector<std::int32_t>& order) {
  EdgeStats out;
  out.count = int(order.size());
  out.column = stats.column;
  out.words = stats.words;
  out.blocks = stats.blocks;
  const std::size_t words = std::size_t(stats.words), block_floats = std::size_t(stats.blocks) * 3;
  out.masks.resize(order.size() * words);
  out.sums.resize(order.size() * 3);
  out.block_sums.resize(order.size() * block_floats);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::size_t from = std::size_t(order[i]);
    std::copy_n(stats.masks.data() + from * words, words, out.masks.data() + i * words);
    std::copy_n(stats.sums.data() + from * 3, 3, out.sums.data() + i * 3);
    std::copy_n(stats.block_sums.data() + from * block_floats, block_floats,
                out.block_sums.data() + i * block_floats);
  }
  return out;
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
