#include "synth/detail/group_scan.hpp"

#include <algorithm>
#include <bit>

#include "core/error.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace tw::detail {
namespace {

constexpr int kLanes = 64;  // groups per qualifying() call

struct Layout {
  const std::int64_t* group_min;
  const std::uint64_t* masks;
  int count, words, stride, shift;
};

std::uint64_t qualifying_scalar(const Layout& in, const std::uint64_t* key, int g0,
                                std::int64_t best) {
  std::uint64_t out = 0;
  for (int i = 0; i < in.count; ++i) {
    int m = 0;
    for (int w = 0; w < in.words; ++w)
      m += std::popcount(in.masks[std::size_t(w) * in.stride + g0 + i] ^ key[w]);
    if (in.group_min[g0 + i] + (std::int64_t(m) << in.shift) <= best) out |= std::uint64_t(1) << i;
  }
  return out;
}

#if defined(__x86_64__)
// GCC 12 reports the intrinsics' own undefined pass-through operand as maybe uninitialized.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
__attribute__((target("avx512f,avx512vpopcntdq"))) std::uint64_t qualifying_avx512(
    const Layout& in, const std::uint64_t* key, int g0, std::int64_t best) {
  std::uint64_t out = 0;
  const __m512i limit = _mm512_set1_epi64(best), shift = _mm512_set1_epi64(in.shift);
  for (int i = 0; i < in.count; i += 8) {
    __m512i m = _mm512_setzero_si512();
    for (int w = 0; w < in.words; ++w) {
      const __m512i x =
          _mm512_xor_si512(_mm512_loadu_si512(in.masks + std::size_t(w) * in.stride + g0 + i),
                           _mm512_set1_epi64(std::int64_t(key[w])));
      m = _mm512_add_epi64(m, _mm512_popcnt_epi64(x));
    }
    const __m512i bound =
        _mm512_add_epi64(_mm512_loadu_si512(in.group_min + g0 + i), _mm512_sllv_epi64(m, shift));
    out |= std::uint64_t(_mm512_cmple_epi64_mask(bound, limit)) << i;
  }
  return in.count < kLanes ? out & ((std::uint64_t(1) << in.count) - 1) : out;
}
#pragma GCC diagnostic pop
#endif

using Qualifying = std::uint64_t (*)(const Layout&, const std::uint64_t*, int, std::int64_t);

Qualifying pick() {
#if defined(__x86_64__)
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vpopcntdq"))
    return qualifying_avx512;
#endif
  return qualifying_scalar;
}

}  // namespace

GroupScan::GroupScan(const std::vector<std::int64_t>& group_min,
                     const std::vector<std::uint64_t>& group_masks, int words,
                     std::int64_t mismatch, bool vector)
    : groups_(int(group_min.size())), words_(words), vector_(vector) {
  if (mismatch <= 0 || !std::has_single_bit(std::uint64_t(mismatch)))
    fail("group scan: the mismatch cost {} is not a power of two", mismatch);
  shift_ = std::countr_zero(std::uint64_t(mismatch));
  // Whole 64-group blocks, so every vector load stays inside; padding lanes are masked off.
  stride_ = (groups_ + kLanes - 1) / kLanes * kLanes;
  group_min_.assign(std::size_t(stride_), 0);
  std::copy(group_min.begin(), group_min.end(), group_min_.begin());
  masks_.assign(std::size_t(stride_) * words_, 0);
  for (int g = 0; g < groups_; ++g)
    for (int w = 0; w < words_; ++w)
      masks_[std::size_t(w) * stride_ + g] = group_masks[std::size_t(g) * words_ + w];
}

std::uint64_t GroupScan::qualifying(const std::uint64_t* key, int g0, std::int64_t best) const {
  static const Qualifying run = pick();
  const Layout in{group_min_.data(), masks_.data(), std::min(kLanes, groups_ - g0), words_,
                  stride_,           shift_};
  return vector_ ? run(in, key, g0, best) : qualifying_scalar(in, key, g0, best);
}

}  // namespace tw::detail
