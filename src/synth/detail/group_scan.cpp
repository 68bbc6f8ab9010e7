#include "synth/detail/group_scan.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <numeric>

#include "core/error.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace tw::detail {
namespace {

constexpr int kPad = 8;  // entries per vector: buckets are padded to a multiple

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
  return in.count < 64 ? out & ((std::uint64_t(1) << in.count) - 1) : out;
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
                     const std::vector<std::uint64_t>& group_masks, int words, int column,
                     std::int64_t mismatch, bool vector)
    : words_(words), vector_(vector) {
  if (mismatch <= 0 || !std::has_single_bit(std::uint64_t(mismatch)))
    fail("group scan: the mismatch cost {} is not a power of two", mismatch);
  shift_ = std::countr_zero(std::uint64_t(mismatch));
  const int groups = int(group_min.size());
  std::vector<int> count(static_cast<std::size_t>(groups), 0);
  for (int g = 0; g < groups; ++g)
    for (int w = 0; w < words; ++w)
      count[std::size_t(g)] += std::popcount(group_masks[std::size_t(g) * words + w]);
  std::vector<std::int32_t> order(static_cast<std::size_t>(groups));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    if (count[std::size_t(a)] != count[std::size_t(b)])
      return count[std::size_t(a)] < count[std::size_t(b)];
    return group_min[std::size_t(a)] < group_min[std::size_t(b)];
  });
  bucket_begin_.assign(std::size_t(column) + 2, 0);
  std::size_t next = 0;
  for (int c = 0; c <= column; ++c) {
    bucket_begin_[std::size_t(c)] = std::int32_t(group_.size());
    for (; next < order.size() && count[std::size_t(order[next])] == c; ++next)
      group_.push_back(order[next]);
    while (group_.size() % kPad) group_.push_back(-1);
  }
  if (next != order.size()) fail("group scan: a mask has more than {} opaque samples", column);
  bucket_begin_[std::size_t(column) + 1] = std::int32_t(group_.size());
  const std::size_t entries = group_.size();
  lowest_.assign(entries, std::numeric_limits<std::int64_t>::max() / 4);
  masks_.assign(entries * std::size_t(words), 0);
  for (std::size_t i = 0; i < entries; ++i) {
    const int g = group_[i];
    if (g < 0) continue;
    lowest_[i] = group_min[std::size_t(g)];
    for (int w = 0; w < words; ++w)
      masks_[std::size_t(w) * entries + i] = group_masks[std::size_t(g) * words + w];
  }
}

std::uint64_t GroupScan::qualifying(const std::uint64_t* key, int i0, int count,
                                    std::int64_t best) const {
  static const Qualifying run = pick();
  // Vector loads read whole 8-entry blocks, which padding keeps inside the arrays.
  const Layout in{lowest_.data(), masks_.data(), std::min(count, 64), words_, entries(), shift_};
  return vector_ ? run(in, key, i0, best) : qualifying_scalar(in, key, i0, best);
}

}  // namespace tw::detail
