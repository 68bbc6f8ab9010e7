#include "synth/detail/dp_driver.hpp"

#include <algorithm>
#include <chrono>

#include "core/error.hpp"

namespace tw::detail {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

bool same_shape(const PieceFootprint& a, const PieceFootprint& b) {
  auto same = [](const std::vector<TexelOffset>& x, const std::vector<TexelOffset>& y) {
    return x.size() == y.size() && std::equal(x.begin(), x.end(), y.begin(), [](auto p, auto q) {
             return p.dx == q.dx && p.dy == q.dy;
           });
  };
  return a.min_opaque == b.min_opaque && same(a.must_be_clear, b.must_be_clear) &&
         same(a.interior, b.interior);
}

// PassOptions::remaining: keeps the entries of `row` whose cost plus remaining cost can still
// reach the limit; false when none is left.
bool drop_losers(const PassOptions& options, int r, Row& row, std::vector<std::int64_t>& cost) {
  const std::vector<std::int64_t>& remaining = options.remaining(r);
  std::size_t kept = 0;
  for (std::size_t j = 0; j < cost.size(); ++j) {
    if (cost[j] > options.limit - remaining[j]) continue;
    row.indices[kept] = row.indices[j];
    row.argmin[kept] = row.argmin[j];
    cost[kept++] = cost[j];
  }
  row.indices.resize(kept), row.argmin.resize(kept), cost.resize(kept);
  return kept > 0;
}

}  // namespace

std::int32_t best_entry(const std::vector<std::int64_t>& cost) {
  std::int32_t best = -1;
  for (std::size_t j = 0; j < cost.size(); ++j)
    if (best < 0 || cost[j] < cost[std::size_t(best)]) best = std::int32_t(j);
  return best;
}

const std::vector<std::vector<std::int32_t>>& DpDriver::valid_positions() {
  valid_.assign(input_.pieces.size(), {});
  unary_.clear();
  std::vector<std::uint8_t> flags;
  std::vector<std::int32_t> shape_valid;  // of the last shape, before keep_positions
  for (std::size_t i = 0; i < input_.pieces.size(); ++i) {
    const PieceFootprint& p = input_.pieces[i];
    if (i == 0 || !same_shape(p, input_.pieces[i - 1])) {
      auto start = Clock::now();
      backend_.find_valid_positions(*input_.texels, input_.space, p, flags);
      timings_.find_valid_ms += ms_since(start);
      start = Clock::now();
      backend_.compact_valid_positions(flags, shape_valid);
      timings_.compact_ms += ms_since(start);
    }
    valid_[i] = shape_valid;
    if (input_.keep_positions) input_.keep_positions(int(i), valid_[i]);
    if (with_unary()) {
      // A piece of the same shape at the same positions pays the same coverage costs.
      if (i > 0 && same_shape(p, input_.pieces[i - 1]) && valid_[i] == valid_[i - 1]) {
        unary_.push_back(unary_.back());
      } else {
        unary_.emplace_back();
        coverage_costs(*input_.texels, input_.space, p, input_.coverage, valid_[i], unary_.back());
      }
    }
  }
  return valid_;
}

Pass DpDriver::forward(const std::vector<std::int32_t>& first_row, int row_count,
                       const RowIndices& row_indices, const PassOptions& options) {
  const int N = int(input_.pieces.size());
  Pass pass;
  if (options.record) options.record->clear();
  pass.rows.reserve(std::size_t(row_count));
  std::vector<std::int64_t> cost, next_cost;
  pass.rows.push_back({first_row, {}, first_row.empty(), -1});
  if (first_row.empty()) {
    require_empty_allowed(0);
    cost.assign(1, empty_piece_penalty(input_.space.column));
  } else {
    cost.assign(first_row.size(), 0);
    add_unary(0, first_row, cost);
  }
  if (options.record) options.record->push_back(cost);
  for (int r = 1; r < row_count; ++r) {
    const PieceFootprint& previous_piece = input_.pieces[std::size_t(r - 1)];
    const std::vector<std::int32_t>& indices = row_indices(r);
    const Row& previous = pass.rows.back();
    Row row;
    row.indices = indices;
    if (indices.empty()) {
      require_empty_allowed(r % N);
      row.empty = true;
      row.empty_from = previous.empty ? -1 : best_entry(cost);
      next_cost.assign(1, cost[std::size_t(std::max(0, row.empty_from))] +
                              empty_piece_penalty(input_.space.column));
    } else if (previous.empty) {
      next_cost.assign(indices.size(), cost[0]);
      row.argmin.assign(indices.size(), -1);
      if (r < N) add_unary(r, indices, next_cost);
    } else {
      // The following row's edges, when it runs an update too: a device backend extracts
      // them while this row's update runs.
      const RowEdges edges{&previous_piece, &previous.indices, &indices};
      RowEdges following;
      if (r + 1 < row_count && !row_indices(r + 1).empty() && !options.remaining)
        following = {&input_.pieces[std::size_t(r)], &indices, &row_indices(r + 1)};
      if (input_.exemplar_switch.active())
        switching_row(edges, cost, next_cost, row.argmin);
      else
        timed_row(edges, following.indices ? &following : nullptr, cost, next_cost, row.argmin);
      if (r < N) add_unary(r, indices, next_cost);  // the terminal row is piece 0, paid in row 0
      ++timings_.rows;
    }
    if (options.remaining && r < N && !drop_losers(options, r, row, next_cost)) {
      pass.aborted = true;
      return pass;
    }
    if (options.record && r < N) options.record->push_back(next_cost);
    cost.swap(next_cost);
    pass.rows.push_back(std::move(row));
    if (options.progress) options.progress->advance();
  }
  pass.last_cost = std::move(cost);
  return pass;
}

void DpDriver::timed_row(const RowEdges& edges, const RowEdges* following,
                         const std::vector<std::int64_t>& cost, std::vector<std::int64_t>& next_cost,
                         std::vector<std::int32_t>& argmin) {
  RowTimes times;
  backend_.dp_row(*input_.texels, input_.space, edges, following, cost, next_cost, argmin, times);
  timings_.extract_ms += times.extract_ms;
  timings_.update_ms += times.update_ms;
}

// A row under a switching cost: for the current positions of each exemplar e, one update over
// every previous position with P'[v] = P[v] + cost * [exemplar(v) != e]. That is the update with
// D' = D + cost * [exemplar change] exactly (same minimum, same lowest-v ties), and D keeps its
// pruning bounds.
void DpDriver::switching_row(const RowEdges& edges, const std::vector<std::int64_t>& cost,
                             std::vector<std::int64_t>& next_cost,
                             std::vector<std::int32_t>& argmin) {
  const ExemplarSwitch& change = input_.exemplar_switch;
  const std::vector<std::int32_t>& indices = *edges.indices;
  std::vector<int> previous_exemplar, exemplar;
  for (std::int32_t v : *edges.previous_indices) previous_exemplar.push_back(change.exemplar(v));
  for (std::int32_t j : indices) exemplar.push_back(change.exemplar(j));
  std::vector<int> exemplars = exemplar;
  std::sort(exemplars.begin(), exemplars.end());
  exemplars.erase(std::unique(exemplars.begin(), exemplars.end()), exemplars.end());
  next_cost.assign(indices.size(), 0);
  argmin.assign(indices.size(), -1);
  std::vector<std::int32_t> subset, sub_argmin;
  std::vector<std::int64_t> shifted(cost.size()), sub_cost;
  for (int e : exemplars) {
    subset.clear();
    for (std::size_t j = 0; j < indices.size(); ++j)
      if (exemplar[j] == e) subset.push_back(indices[j]);
    for (std::size_t v = 0; v < cost.size(); ++v)
      shifted[v] = cost[v] + (previous_exemplar[v] != e ? change.cost : 0);
    timed_row({edges.previous_piece, edges.previous_indices, &subset}, nullptr, shifted, sub_cost,
              sub_argmin);
    for (std::size_t j = 0, k = 0; j < indices.size(); ++j)
      if (exemplar[j] == e) next_cost[j] = sub_cost[k], argmin[j] = sub_argmin[k++];
  }
}

// Row updates with the edges swapped: D is symmetric (xi(p, q) = xi(q, p)), so the "previous"
// columns are the next row's left edges and the "current" ones this row's right edges. Without
// the switching cost (it is >= 0): still a lower bound of what remains, which is all the cycle
// search asks of it.
std::vector<std::vector<std::int64_t>> DpDriver::remaining_costs(
    const std::vector<std::int32_t>& terminal) {
  const auto& valid = valid_;
  const std::size_t N = valid.size();
  std::vector<std::vector<std::int64_t>> remaining(N);
  std::vector<std::int64_t> next(terminal.size(), 0);
  std::vector<std::int32_t> argmin;
  ColumnSet lefts, rights;
  for (std::size_t r = N; r-- > 0;) {
    auto start = Clock::now();
    backend_.extract_left_columns(*input_.texels, input_.space, r + 1 < N ? valid[r + 1] : terminal,
                                  lefts);
    backend_.extract_right_columns(*input_.texels, input_.space, input_.pieces[r], valid[r],
                                   rights);
    timings_.extract_ms += ms_since(start);
    start = Clock::now();
    backend_.update_table_row(next, lefts, rights, remaining[r], argmin);
    timings_.update_ms += ms_since(start);
    ++timings_.rows;
    next = remaining[r];
    add_unary(int(r), valid[r], next);
  }
  return remaining;
}

// cost[j] += the unary cost of piece `piece` at indices[j] (ascending): cached for the piece's
// valid positions, computed for others.
void DpDriver::add_unary(int piece, const std::vector<std::int32_t>& indices,
                         std::vector<std::int64_t>& cost) const {
  if (!with_unary()) return;
  const std::vector<std::int32_t>& valid = valid_[std::size_t(piece)];
  const std::vector<std::int64_t>& unary = unary_[std::size_t(piece)];
  if (indices == valid) {
    for (std::size_t j = 0; j < cost.size(); ++j) cost[j] += unary[j];
    return;
  }
  std::vector<std::int64_t> own;
  for (std::size_t j = 0; j < cost.size(); ++j) {
    const auto at = std::lower_bound(valid.begin(), valid.end(), indices[j]);
    if (at != valid.end() && *at == indices[j]) {
      cost[j] += unary[std::size_t(at - valid.begin())];
    } else {
      coverage_costs(*input_.texels, input_.space, input_.pieces[std::size_t(piece)],
                     input_.coverage, {indices[j]}, own);
      cost[j] += own[0];
    }
  }
}

void DpDriver::require_empty_allowed(int piece) const {
  if (input_.allow_empty) return;
  if (input_.no_valid_message) throw Error(input_.no_valid_message(piece));
  fail("piece {}: no valid position in the exemplar", piece);
}

// Positions per row, backtracked from entry `entry` of the last row.
std::vector<std::int32_t> backtrack(const Pass& pass, std::int32_t entry) {
  std::vector<std::int32_t> positions(pass.rows.size(), -1);
  for (std::size_t r = pass.rows.size(); r-- > 0;) {
    const Row& row = pass.rows[r];
    if (row.empty) {
      entry = row.empty_from;
      continue;
    }
    positions[r] = row.indices[std::size_t(entry)];
    entry = row.argmin.empty() ? -1 : row.argmin[std::size_t(entry)];
  }
  return positions;
}

}  // namespace tw::detail
