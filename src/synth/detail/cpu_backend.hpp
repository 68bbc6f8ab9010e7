#pragma once
// The CPU reference backend: TBB-parallel, exact, with the pruned row update of
// synth/detail/edge_bound.hpp. Deterministic for any thread count (each entry of a row is
// computed by one task, ties broken by the lowest previous index).
#include <memory>

#include "synth/detail/stages.hpp"

namespace tw::detail {

std::unique_ptr<Backend> make_cpu_backend();

// Every pair, every sample: the definition the pruned row must equal (used by tests).
void update_table_row_naive(const std::vector<std::int64_t>& previous_cost, const ColumnSet& right,
                            const ColumnSet& left, std::vector<std::int64_t>& cost,
                            std::vector<std::int32_t>& argmin);

// The pruned exact row: previous positions visited in increasing (P[v], v), skipped when
// P[v] + bound cannot beat the best, stopped when P[v] alone exceeds it. `pairs_evaluated`
// (optional) receives how many pairs needed the full D.
void update_table_row_pruned(const std::vector<std::int64_t>& previous_cost, const ColumnSet& right,
                             const ColumnSet& left, std::vector<std::int64_t>& cost,
                             std::vector<std::int32_t>& argmin,
                             std::int64_t* pairs_evaluated = nullptr);

}  // namespace tw::detail
