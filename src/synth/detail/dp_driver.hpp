#pragma once
// The DP's row loop on a Backend (used by dp.cpp and closed_cycle.cpp): valid positions,
// forward passes over rows of chosen positions, remaining-cost bounds, backtracking.
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "core/progress.hpp"
#include "synth/detail/dp.hpp"

namespace tw::detail {

inline constexpr std::int64_t kNoCost = std::numeric_limits<std::int64_t>::max();

struct Row {
  std::vector<std::int32_t> indices;
  std::vector<std::int32_t> argmin;  // into the previous row's indices; -1: previous is empty
  bool empty = false;
  std::int32_t empty_from = -1;  // for an empty row: the previous row's entry it continues
};

struct Pass {
  std::vector<Row> rows;
  std::vector<std::int64_t> last_cost;  // of the last row (one entry if it is empty)
  bool aborted = false;                 // PassOptions::remaining dropped a whole row
};

struct PassOptions {
  Progress* progress = nullptr;
  // Exact cycle search: entry j of row r (0 < r < N) is dropped when its cost plus
  // remaining(r)[j], a lower bound of the rest of any path through it, exceeds `limit`; a row
  // left empty aborts the pass. Entries that remain keep their costs and argmins (a dropped
  // argmin would give its row's entry a sum above `limit` too).
  std::function<const std::vector<std::int64_t>&(int)> remaining;
  std::int64_t limit = kNoCost;
  std::vector<std::vector<std::int64_t>>* record = nullptr;  // gets the costs of rows 0..N-1
};

using RowIndices = std::function<const std::vector<std::int32_t>&(int)>;

class DpDriver {
 public:
  DpDriver(Backend& backend, const DpInput& input, DpTimings& timings)
      : backend_(backend), input_(input), timings_(timings) {}

  // Valid indices of every piece (kept by the driver); identical consecutive footprints share
  // one computation.
  const std::vector<std::vector<std::int32_t>>& valid_positions();

  // One forward pass over rows 0..R-1; row r > 0 holds piece r (piece 0 again for the terminal
  // row r = N of a closed curve) at positions `row_indices(r)`, ascending.
  Pass forward(const std::vector<std::int32_t>& first_row, int row_count,
               const RowIndices& row_indices, const PassOptions& options = {});

  // remaining[r][j]: the least cost of rows r+1..N after piece r at valid[r][j] (seams and the
  // unary costs of pieces r+1..N-1), over every continuation to any entry of `terminal`.
  std::vector<std::vector<std::int64_t>> remaining_costs(const std::vector<std::int32_t>& terminal);

 private:
  bool with_unary() const { return input_.coverage.weight_milli > 0; }
  void timed_row(const RowEdges& edges, const RowEdges* following,
                 const std::vector<std::int64_t>& cost, std::vector<std::int64_t>& next_cost,
                 std::vector<std::int32_t>& argmin);
  void switching_row(const RowEdges& edges, const std::vector<std::int64_t>& cost,
                     std::vector<std::int64_t>& next_cost, std::vector<std::int32_t>& argmin);
  void add_unary(int piece, const std::vector<std::int32_t>& indices,
                 std::vector<std::int64_t>& cost) const;
  void require_empty_allowed(int piece) const;

  Backend& backend_;
  const DpInput& input_;
  DpTimings& timings_;
  std::vector<std::vector<std::int32_t>> valid_;  // per piece
  std::vector<std::vector<std::int64_t>> unary_;  // per piece, over its valid positions
};

// Lowest (cost, entry) of a row's costs.
std::int32_t best_entry(const std::vector<std::int64_t>& cost);

// Positions per row, backtracked from entry `entry` of the last row.
std::vector<std::int32_t> backtrack(const Pass& pass, std::int32_t entry);

}  // namespace tw::detail
