#include "synth/detail/edge_bound.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

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
  stats.binary_alpha = columns.binary_alpha;
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
          if (is_opaque(t)) mask[k / 64] |= std::uint64_t(1) << (k % 64);
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
  out.binary_alpha = stats.binary_alpha;
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
  const int m = mismatched_samples(right, a, left, b);
  std::int64_t bound = mismatch_cost(binary_alpha) * m;
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

namespace {

// floor(sqrt(x)) for x = 256 d2 (d2 = squared RGB distance): x is a multiple of 256 below 2^26,
// so float(x) is exact and the correctly rounded square root truncates to floor(sqrt(x)) or one
// more (when it rounds up to the next integer); one comparison corrects it.
inline std::int32_t colour_term_from_squared(std::int32_t d2) {
  const std::int32_t x = 256 * d2;
  const std::int32_t r = std::int32_t(__builtin_sqrtf(float(x)));
  return r * r > x ? r - 1 : r;
}

// xi for binary alpha. Opaque = alpha >= 128 = the top bit (kOpaqueAlphaMin == 128).
inline std::int32_t binary_xi(std::uint32_t p, std::uint32_t q) {
  if ((p ^ q) >> 31) return kGamma;
  const std::int32_t dr = std::int32_t(p & 255u) - std::int32_t(q & 255u);
  const std::int32_t dg = std::int32_t((p >> 8) & 255u) - std::int32_t((q >> 8) & 255u);
  const std::int32_t db = std::int32_t((p >> 16) & 255u) - std::int32_t((q >> 16) & 255u);
  return colour_term_from_squared(dr * dr + dg * dg + db * db);
}

std::int64_t edge_cost_capped_scalar(const std::uint32_t* right, const std::uint32_t* left,
                                     int count, bool binary_alpha, std::int64_t limit) {
  std::int64_t sum = 0;
  for (int k0 = 0; k0 < count; k0 += kBoundBlock) {
    const int k1 = std::min(count, k0 + kBoundBlock);
    std::int32_t block = 0;
    for (int k = k0; k < k1; ++k)
      block += binary_alpha ? binary_xi(right[k], left[k]) : xi(right[k], left[k], false);
    sum += block;
    if (sum > limit) return sum;
  }
  return sum;
}

#if defined(__x86_64__)
// The same sum, 8 samples per AVX2 instruction (binary alpha only), checked against the limit
// every 16 samples.
__attribute__((target("avx2"))) std::int64_t edge_cost_capped_avx2(const std::uint32_t* right,
                                                                   const std::uint32_t* left,
                                                                   int count, std::int64_t limit) {
  const __m256i byte = _mm256_set1_epi32(255), gamma = _mm256_set1_epi32(kGamma);
  auto xi8 = [&](int k) __attribute__((target("avx2"))) {
    const __m256i p = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(right + k));
    const __m256i q = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(left + k));
    const __m256i dr = _mm256_sub_epi32(_mm256_and_si256(p, byte), _mm256_and_si256(q, byte));
    const __m256i dg = _mm256_sub_epi32(_mm256_and_si256(_mm256_srli_epi32(p, 8), byte),
                                        _mm256_and_si256(_mm256_srli_epi32(q, 8), byte));
    const __m256i db = _mm256_sub_epi32(_mm256_and_si256(_mm256_srli_epi32(p, 16), byte),
                                        _mm256_and_si256(_mm256_srli_epi32(q, 16), byte));
    const __m256i d2 =
        _mm256_add_epi32(_mm256_add_epi32(_mm256_mullo_epi32(dr, dr), _mm256_mullo_epi32(dg, dg)),
                         _mm256_mullo_epi32(db, db));
    const __m256i x = _mm256_slli_epi32(d2, 8);
    __m256i r = _mm256_cvttps_epi32(_mm256_sqrt_ps(_mm256_cvtepi32_ps(x)));
    r = _mm256_add_epi32(r, _mm256_cmpgt_epi32(_mm256_mullo_epi32(r, r), x));  // -1 if too big
    const __m256i mismatch = _mm256_srai_epi32(_mm256_xor_si256(p, q), 31);
    return _mm256_blendv_epi8(r, gamma, mismatch);
  };
  std::int64_t sum = 0;
  int k = 0;
  for (; k + 16 <= count; k += 16) {
    const __m256i v = _mm256_add_epi32(xi8(k), xi8(k + 8));
    __m128i h = _mm_add_epi32(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1));
    h = _mm_add_epi32(h, _mm_shuffle_epi32(h, 0x4e));
    h = _mm_add_epi32(h, _mm_shuffle_epi32(h, 0xb1));
    sum += _mm_cvtsi128_si32(h);
    if (sum > limit) return sum;
  }
  for (; k < count; ++k) sum += binary_xi(right[k], left[k]);
  return sum;
}
#endif

}  // namespace

std::int64_t edge_cost_capped(const std::uint32_t* right, const std::uint32_t* left, int count,
                              bool binary_alpha, std::int64_t limit) {
#if defined(__x86_64__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (binary_alpha && avx2) return edge_cost_capped_avx2(right, left, count, limit);
#endif
  return edge_cost_capped_scalar(right, left, count, binary_alpha, limit);
}

static_assert(kOpaqueAlphaMin == 128, "edge_cost_capped reads opacity from the top bit");
static_assert(kMismatchExtra == kGamma - kMaxColourTerm - 1);

}  // namespace tw::detail
