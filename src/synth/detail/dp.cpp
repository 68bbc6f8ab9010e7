#include "synth/detail/dp.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>
#include <numeric>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/progress.hpp"
#include "synth/detail/cost.hpp"

namespace tw::detail {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::int64_t kNoCost = std::numeric_limits<std::int64_t>::max();

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct Row {
  std::vector<std::int32_t> indices;
  std::vector<std::int32_t> argmin;  // into the previous row's indices; -1: previous is empty
  bool empty = false;
  std::int32_t empty_from = -1;  // for an empty row: the previous row's entry it continues
};

struct Pass {
  std::vector<Row> rows;
  std::vector<std::int64_t> last_cost;  // of the last row (one entry if it is empty)
};

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Lowest (cost, entry) of a row's costs.
std::int32_t best_entry(const std::vector<std::int64_t>& cost) {
  std::int32_t best = -1;
  for (std::size_t j = 0; j < cost.size(); ++j)
    if (best < 0 || cost[j] < cost[std::size_t(best)]) best = std::int32_t(j);
  return best;
}

class Driver {
 public:
  Driver(Backend& backend, const DpInput& input, DpTimings& timings)
      : backend_(backend), input_(input), timings_(timings) {}

  // Valid indices of every piece; identical consecutive footprints share one computation.
  std::vector<std::vector<std::int32_t>> valid_positions() {
    std::vector<std::vector<std::int32_t>> valid(input_.pieces.size());
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
      valid[i] = shape_valid;
      if (input_.keep_positions) input_.keep_positions(int(i), valid[i]);
      if (with_unary()) {
        // A piece of the same shape at the same positions pays the same coverage costs.
        if (i > 0 && same_shape(p, input_.pieces[i - 1]) && valid[i] == valid[i - 1]) {
          unary_.push_back(unary_.back());
        } else {
          unary_.emplace_back();
          coverage_costs(*input_.texels, input_.space, p, input_.coverage, valid[i], unary_.back());
        }
      }
    }
    valid_sizes_.clear();
    for (const auto& v : valid) valid_sizes_.push_back(v.size());
    return valid;
  }

  // One forward pass over rows 0..R-1; row r > 0 holds piece r (piece 0 again for the terminal
  // row r = N of a closed curve) at positions `row_indices(r)`.
  Pass forward(const std::vector<std::int32_t>& first_row, int row_count,
               const std::function<const std::vector<std::int32_t>&(int)>& row_indices,
               Progress* progress) {
    const int N = int(input_.pieces.size());
    Pass pass;
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
        if (r + 1 < row_count && !row_indices(r + 1).empty())
          following = {&input_.pieces[std::size_t(r)], &indices, &row_indices(r + 1)};
        if (input_.exemplar_switch.active())
          switching_row(edges, cost, next_cost, row.argmin);
        else
          timed_row(edges, following.indices ? &following : nullptr, cost, next_cost, row.argmin);
        if (r < N) add_unary(r, indices, next_cost);  // the terminal row is piece 0, paid in row 0
        ++timings_.rows;
      }
      cost.swap(next_cost);
      pass.rows.push_back(std::move(row));
      if (progress) progress->advance();
    }
    pass.last_cost = std::move(cost);
    return pass;
  }

 private:
  bool with_unary() const { return input_.coverage.weight_milli > 0; }

  void timed_row(const RowEdges& edges, const RowEdges* following,
                 const std::vector<std::int64_t>& cost, std::vector<std::int64_t>& next_cost,
                 std::vector<std::int32_t>& argmin) {
    RowTimes times;
    backend_.dp_row(*input_.texels, input_.space, edges, following, cost, next_cost, argmin, times);
    timings_.extract_ms += times.extract_ms;
    timings_.update_ms += times.update_ms;
  }

  // A row under a switching cost: for the current positions of each exemplar e, one update
  // over every previous position with P'[v] = P[v] + cost * [exemplar(v) != e]. That is the
  // update with D' exactly (same minimum, same lowest-v ties), and D keeps its pruning bounds.
  void switching_row(const RowEdges& edges, const std::vector<std::int64_t>& cost,
                     std::vector<std::int64_t>& next_cost, std::vector<std::int32_t>& argmin) {
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

  // cost[j] += the unary cost of piece `piece` at indices[j]: cached for the piece's valid
  // positions, computed for a fixed or drawn first position.
  void add_unary(int piece, const std::vector<std::int32_t>& indices,
                 std::vector<std::int64_t>& cost) const {
    if (!with_unary()) return;
    const std::vector<std::int64_t>* unary = &unary_[std::size_t(piece)];
    std::vector<std::int64_t> own;
    if (indices.size() != valid_sizes_[std::size_t(piece)]) {
      coverage_costs(*input_.texels, input_.space, input_.pieces[std::size_t(piece)],
                     input_.coverage, indices, own);
      unary = &own;
    }
    for (std::size_t j = 0; j < cost.size(); ++j) cost[j] += (*unary)[j];
  }

  static bool same_shape(const PieceFootprint& a, const PieceFootprint& b) {
    auto same = [](const std::vector<TexelOffset>& x, const std::vector<TexelOffset>& y) {
      return x.size() == y.size() && std::equal(x.begin(), x.end(), y.begin(), [](auto p, auto q) {
               return p.dx == q.dx && p.dy == q.dy;
             });
    };
    return a.min_opaque == b.min_opaque && same(a.must_be_clear, b.must_be_clear) &&
           same(a.interior, b.interior);
  }

  void require_empty_allowed(int piece) const {
    if (input_.allow_empty) return;
    if (input_.no_valid_message) throw Error(input_.no_valid_message(piece));
    fail("piece {}: no valid position in the exemplar", piece);
  }

  Backend& backend_;
  const DpInput& input_;
  DpTimings& timings_;
  std::vector<std::vector<std::int64_t>> unary_;  // per piece, over its valid positions
  std::vector<std::size_t> valid_sizes_;
};

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

}  // namespace

std::int64_t empty_piece_penalty(int column) {
  return std::int64_t(kGamma) * column * 2;
}

std::int64_t seam_cost(const CostTexels& texels, const PositionSpace& space,
                       const PieceFootprint& piece, std::int32_t a, std::int32_t b) {
  const std::int32_t X0 = space.ux(a) * 256 - 128, Y0 = space.uy(a) * 256 - 128;
  std::int64_t sum = 0;
  for (int k = 0; k < piece.column; ++k) {
    const std::uint32_t right =
        sample_bilinear(texels, X0 + piece.right_fx[k], Y0 + piece.right_fy[k]);
    const std::uint32_t left = texel_at(texels, space.ux(b), space.uy(b) + k);
    sum += xi(right, left, texels.binary_alpha);
  }
  return sum;
}

std::int64_t sequence_cost(const CostTexels& texels, const PositionSpace& space,
                           const std::vector<PieceFootprint>& pieces,
                           const std::vector<std::int32_t>& positions, bool closed) {
  std::int64_t sum = 0;
  for (std::size_t i = 0; i + 1 < positions.size(); ++i)
    sum += seam_cost(texels, space, pieces[i], positions[i], positions[i + 1]);
  if (closed && !positions.empty())
    sum += seam_cost(texels, space, pieces.back(), positions.back(), positions.front());
  return sum;
}

int exemplar_switches(const std::vector<std::int32_t>& positions, bool closed,
                      const std::function<int(std::int32_t)>& exemplar) {
  const std::size_t n = positions.size();
  const std::size_t seams = closed && n > 1 ? n : (n > 0 ? n - 1 : 0);
  int switches = 0;
  for (std::size_t i = 0; i < seams; ++i) {
    const std::int32_t a = positions[i], b = positions[(i + 1) % n];
    if (a >= 0 && b >= 0 && exemplar(a) != exemplar(b)) ++switches;
  }
  return switches;
}

std::int64_t objective_cost(const CostTexels& texels, const PositionSpace& space,
                            const std::vector<PieceFootprint>& pieces,
                            const std::vector<std::int32_t>& positions, bool closed,
                            const CoverageTerm& coverage, const ExemplarSwitch& change) {
  std::int64_t sum = sequence_cost(texels, space, pieces, positions, closed);
  if (change.active()) sum += change.cost * exemplar_switches(positions, closed, change.exemplar);
  std::vector<std::int64_t> unary;
  for (std::size_t i = 0; i < positions.size() && coverage.weight_milli > 0; ++i) {
    coverage_costs(texels, space, pieces[i], coverage, {positions[i]}, unary);
    sum += unary[0];
  }
  return sum;
}

DpResult run_dp(Backend& backend, const DpInput& input) {
  const int N = int(input.pieces.size());
  if (N == 0) fail("synthesis needs at least one piece");
  DpResult result;
  Driver driver(backend, input, result.timings);
  const auto valid = driver.valid_positions();
  for (const auto& v : valid) result.valid_counts.push_back(int(v.size()));

  std::vector<std::int32_t> first_row = valid[0];
  if (input.first_index) {
    if (!std::binary_search(valid[0].begin(), valid[0].end(), *input.first_index))
      fail("the fixed first position ({}, {}) is not a valid position for piece 0",
           input.space.ux(*input.first_index), input.space.uy(*input.first_index));
    first_row = {*input.first_index};
  } else if (input.seed != 0 && !valid[0].empty()) {
    first_row = {valid[0][splitmix64(input.seed) % valid[0].size()]};
  }

  const int rows = input.closed ? N + 1 : N;
  std::unique_ptr<Progress> progress;
  if (rows >= 64) {
    progress = std::make_unique<Progress>(
        input.label.empty() ? "synthesis DP rows" : input.label + ": DP rows", rows - 1);
  }
  auto free_rows = [&](const std::vector<std::int32_t>& terminal) {
    return [&valid, &terminal, N](int r) -> const std::vector<std::int32_t>& {
      return r < N ? valid[std::size_t(r)] : terminal;
    };
  };
  const Pass pass = driver.forward(first_row, rows, free_rows(first_row), progress.get());

  auto start = Clock::now();
  if (!input.closed) {
    const std::int32_t entry = pass.rows.back().empty ? 0 : best_entry(pass.last_cost);
    result.positions = backtrack(pass, entry);
    result.total_cost = pass.last_cost[std::size_t(entry)];
    result.timings.backtrack_ms += ms_since(start);
    return result;
  }

  // Closed: the terminal row N stands for piece 0 again; a cycle has equal first and terminal
  // positions. Approximation: backtrack from terminal entries in increasing (cost, entry).
  const Row& terminal = pass.rows.back();
  std::vector<std::int32_t> order(terminal.indices.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return pass.last_cost[a] != pass.last_cost[b] ? pass.last_cost[a] < pass.last_cost[b] : a < b;
  });
  std::int64_t best_cost = kNoCost;
  std::int32_t best_start = std::numeric_limits<std::int32_t>::max();
  for (std::int32_t entry : order) {
    auto positions = backtrack(pass, entry);
    if (positions.front() != positions.back()) continue;
    best_cost = pass.last_cost[std::size_t(entry)];
    best_start = positions.front();
    positions.pop_back();
    result.positions = std::move(positions);
    result.approximate_cycle_cost = best_cost;
    break;
  }
  result.timings.backtrack_ms += ms_since(start);
  if (terminal.empty) fail("closed curve: piece 0 has no valid position to close the cycle");
  if (!input.exact_cycle && result.approximate_cycle_cost >= 0) {
    result.total_cost = best_cost;
    return result;
  }
  if (!input.exact_cycle)
    logger().info(
        "closed curve: the single-DP approximation found no cycle; running the exact mode");

  // Exact: one DP per start u0, in increasing free-DP terminal cost, which bounds the cost of
  // every cycle through u0 from below; stop once the bound cannot win.
  for (std::int32_t entry : order) {
    const std::int64_t bound = pass.last_cost[std::size_t(entry)];
    const std::int32_t start_index = terminal.indices[std::size_t(entry)];
    if (bound > best_cost || (bound == best_cost && start_index >= best_start)) break;
    const std::vector<std::int32_t> single{start_index};
    const Pass cycle = driver.forward(single, rows, free_rows(single), nullptr);
    ++result.exact_starts_run;
    if (cycle.rows.back().empty) continue;
    const std::int64_t cost = cycle.last_cost[0];
    if (cost < best_cost || (cost == best_cost && start_index < best_start)) {
      best_cost = cost;
      best_start = start_index;
      result.positions = backtrack(cycle, 0);
      result.positions.pop_back();
    }
  }
  if (best_cost == kNoCost) fail("closed curve: no cycle of valid positions exists");
  result.total_cost = best_cost;
  return result;
}

}  // namespace tw::detail
