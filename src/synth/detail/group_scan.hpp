#pragma once
// Which mask groups of a pruned DP row may still hold a winner (synth/detail/mask_groups.hpp,
// cpu_backend.cpp): group g can only win when its lowest P plus the least cost of its m
// mismatched samples, group_min[g] + mismatch * m, is not above the best so far, with
// m = popcount(group mask ^ left mask). Under the pattern objective the previous costs carry
// the unary term, so the best of a current position is often many mismatches above the row's
// lowest P and the test runs over thousands of groups per position: it is done 8 groups per
// instruction (AVX-512 VPOPCNTDQ, chosen at run time; a scalar loop otherwise) over the masks
// stored word-major. The test only decides what to skip: the groups it keeps are a superset of
// those that can win, so results stay exact whatever the instruction set.
#include <cstdint>
#include <vector>

namespace tw::detail {

class GroupScan {
 public:
  // `group_min`: lowest P per group (ascending); `group_masks`: `words` per group, group-major;
  // `mismatch`: the least cost of a mismatched sample (a power of two). `vector` false: the
  // scalar loop whatever the processor (tests compare the two).
  GroupScan(const std::vector<std::int64_t>& group_min,
            const std::vector<std::uint64_t>& group_masks, int words, std::int64_t mismatch,
            bool vector = true);

  int groups() const { return groups_; }
  // Bit i: group g0 + i (i < min(64, groups - g0)) has group_min + mismatch * m <= best for
  // the left mask `key` (`words` words).
  std::uint64_t qualifying(const std::uint64_t* key, int g0, std::int64_t best) const;

 private:
  int groups_ = 0, words_ = 0, stride_ = 0, shift_ = 0;
  bool vector_ = true;
  std::vector<std::int64_t> group_min_;  // padded to stride_
  std::vector<std::uint64_t> masks_;     // word-major: masks_[w * stride_ + g]
};

}  // namespace tw::detail
