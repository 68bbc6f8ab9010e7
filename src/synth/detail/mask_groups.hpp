#pragma once
// The order in which the pruned row update visits the previous positions of a DP row, shared
// by both backends (synth/detail/cpu_backend.cpp, kernels/row_update.cl): grouped by exact
// opaque mask (one bit per sample, alpha >= 128), groups in increasing lowest P, members in
// increasing (P, v). A "slot" is a place in that order.
#include <cstdint>
#include <vector>

namespace tw::detail {

struct MaskGroups {
  std::vector<std::int32_t> position;        // slot -> v
  std::vector<std::int32_t> group_begin;     // group g = slots [group_begin[g], group_begin[g + 1])
  std::vector<std::int32_t> groups_by_mask;  // group ids in increasing mask (for look-ups)
  std::vector<std::uint64_t> group_masks;    // `words` per group, in group order
  int words = 0;
  int groups() const { return int(group_begin.size()) - 1; }
};

// `masks`: `words` per previous position v, in v order.
MaskGroups group_by_mask(const std::vector<std::int64_t>& previous_cost, const std::uint64_t* masks,
                         int words);

// The group whose mask equals `key` (`words` words), or -1.
int group_with_mask(const MaskGroups& groups, const std::uint64_t* key);

}  // namespace tw::detail
