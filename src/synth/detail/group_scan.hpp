#pragma once
// Which mask groups of a pruned DP row may still hold a winner (synth/detail/mask_groups.hpp):
// group g can only win when its lowest P plus the least cost of its m mismatched samples,
// lowest(g) + mismatch * m, is not above the best so far, m = popcount(group mask ^ left mask).
// Under the pattern objective the previous costs carry the unary term, so the best of a current
// position is often many mismatches above the row's lowest P and this test ran over thousands
// of groups per position. Two things make it cheap, for the CPU row and the kernel alike
// (kernels/row_update.cl reads this very layout):
// - groups are bucketed by their number of opaque samples c; a left mask with q opaque samples
//   differs from every group of bucket c in m >= max(1, |c - q|) samples, so buckets are visited
//   at growing distance d = |c - q| while the row's lowest P + mismatch * max(1, d) can win,
//   each in increasing lowest P while its lowest P + mismatch * max(1, d) can;
// - the exact test runs 8 groups per instruction (AVX-512 VPOPCNTDQ, chosen at run time; a
//   scalar loop otherwise) over masks stored word-major, buckets padded to 8 entries.
// The test only decides what to skip: the groups it keeps are a superset of those that can win,
// so results stay exact whatever the order and the instruction set.
#include <cstdint>
#include <vector>

namespace tw::detail {

class GroupScan {
 public:
  // `group_min`: lowest P per group; `group_masks`: `words` per group, group-major; `column`:
  // samples per mask (C); `mismatch`: the least cost of a mismatched sample (a power of two).
  // `vector` false: the scalar loop whatever the processor (tests compare the two).
  GroupScan(const std::vector<std::int64_t>& group_min,
            const std::vector<std::uint64_t>& group_masks, int words, int column,
            std::int64_t mismatch, bool vector = true);

  // Entries [bucket_begin(c), bucket_begin(c + 1)) hold the groups of c opaque samples,
  // c in [0, column].
  int bucket_begin(int c) const { return bucket_begin_[std::size_t(c)]; }
  int group(int entry) const { return group_[std::size_t(entry)]; }  // -1: padding
  std::int64_t lowest(int entry) const { return lowest_[std::size_t(entry)]; }
  // Bit k: entry i0 + k (k < count <= 64, entries of one bucket) has
  // lowest + mismatch * m <= best for the left mask `key` (`words` words).
  std::uint64_t qualifying(const std::uint64_t* key, int i0, int count, std::int64_t best) const;

  // The layout, for the kernel: entries, their groups, lowest P and word-major masks
  // (masks()[w * entries() + i]), bucket_begin for c in [0, column + 1].
  int entries() const { return int(group_.size()); }
  const std::vector<std::int32_t>& bucket_begins() const { return bucket_begin_; }
  const std::vector<std::int32_t>& groups() const { return group_; }
  const std::vector<std::int64_t>& lowests() const { return lowest_; }
  const std::vector<std::uint64_t>& masks() const { return masks_; }

 private:
  int words_ = 0, shift_ = 0;
  bool vector_ = true;
  std::vector<std::int32_t> bucket_begin_, group_;
  std::vector<std::int64_t> lowest_;
  std::vector<std::uint64_t> masks_;
};

}  // namespace tw::detail
