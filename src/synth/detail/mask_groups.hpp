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

// The half of group_by_mask that does not depend on the costs: the previous positions' runs of
// equal masks, in increasing mask. A device backend finds them for the next row while this
// row's kernel runs, so that only group_runs_by_cost waits for the costs.
struct MaskRuns {
  std::vector<std::int32_t> run_of;      // v -> run
  std::vector<std::int32_t> run_size;    // positions per run
  std::vector<std::uint64_t> run_masks;  // `words` per run
  int words = 0;
  int runs() const { return int(run_size.size()); }
};

MaskRuns mask_runs(const std::uint64_t* masks, int count, int words);

// The run whose mask equals `key` (`words` words), or -1; its group is groups_by_mask[run].
int run_with_mask(const MaskRuns& runs, const std::uint64_t* key);

// group_by_mask(previous_cost, masks, words) given mask_runs(masks, previous_cost.size(), words).
MaskGroups group_runs_by_cost(const MaskRuns& runs, const std::vector<std::int64_t>& previous_cost);

// The group whose mask equals `key` (`words` words), or -1.
int group_with_mask(const MaskGroups& groups, const std::uint64_t* key);

}  // namespace tw::detail
