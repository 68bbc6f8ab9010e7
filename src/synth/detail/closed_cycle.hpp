#pragma once
// Closed curves (Section 1.5): the single-DP approximation's cycle and the exact cycle search.
#include <cstdint>
#include <vector>

#include "synth/detail/dp_driver.hpp"

namespace tw::detail {

// Closed curves. The best cycle so far, lexicographic (cost, start index); positions without
// the terminal row.
struct CycleSearch {
  std::int64_t cost = kNoCost;
  std::int32_t start = std::numeric_limits<std::int32_t>::max();
  std::vector<std::int32_t> positions;

  // Can a cycle through `start` whose cost is at least `bound` still win?
  bool may_win(std::int64_t bound, std::int32_t at) const {
    return bound < cost || (bound == cost && at < start);
  }
};

// A start whose cycles cost at least `bound`.
struct Bounded {
  std::int64_t bound = 0;
  std::int32_t start = 0;
};

// A pass whose first row and terminal row are the same set G of starts gives, at terminal
// entry t, the cheapest path from any start of G to t: a lower bound of every cycle through t,
// and the cost of the cheapest one when the backtracked path starts at t. Records such cycles
// in `search` and returns the starts of G that may still win, ascending.
std::vector<Bounded> examine(const Pass& pass, CycleSearch& search);

// The exact cycle: the minimum over starts u0 of a DP with piece 0 and the terminal row fixed
// to u0 (Section 1.5), by branch and bound over sets of starts instead of one DP per start. A
// set G runs one pass with G as its first and terminal rows (`examine`): its terminal costs
// bound every cycle through each start from below, tighter as G shrinks, and close some of
// them; the starts that may still win are split in two halves by index, cheapest bound first,
// until every start is closed or bounded out. A single start's pass is the per-start DP, and
// a cycle that a larger set closes backtracks to the same positions as that start's own DP (its
// costs along the path equal the single start's, and argmins take the lowest index), so the
// result is the per-start definition's, ties included (brute-force tests).
// `root` is the pass of run_dp with `first_row` (its costs of rows 0..N-1 in `root_costs`) and
// `open` what examine left of it; adds the passes it runs to `passes`.
void exact_cycle(DpDriver& driver, int rows, const std::vector<std::vector<std::int32_t>>& valid,
                 const std::vector<std::int32_t>& first_row,
                 const std::vector<std::vector<std::int64_t>>& root_costs,
                 std::vector<Bounded> open, CycleSearch& search, int& passes);

}  // namespace tw::detail
