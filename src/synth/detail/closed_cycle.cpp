#include "synth/detail/closed_cycle.hpp"

#include <algorithm>
#include <numeric>
#include <queue>

namespace tw::detail {

std::vector<Bounded> examine(const Pass& pass, CycleSearch& search) {
  const Row& terminal = pass.rows.back();
  std::vector<std::int32_t> order(terminal.indices.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return pass.last_cost[a] != pass.last_cost[b] ? pass.last_cost[a] < pass.last_cost[b] : a < b;
  });
  std::vector<Bounded> open;
  for (const std::int32_t entry : order) {
    const std::int64_t bound = pass.last_cost[std::size_t(entry)];
    const std::int32_t start = terminal.indices[std::size_t(entry)];
    if (bound > search.cost) break;
    if (!search.may_win(bound, start)) continue;
    auto positions = backtrack(pass, entry);
    if (positions.front() == positions.back()) {
      positions.pop_back();
      search = {bound, start, std::move(positions)};
    } else {
      open.push_back({bound, start});
    }
  }
  std::erase_if(open, [&](const Bounded& b) { return !search.may_win(b.bound, b.start); });
  std::sort(open.begin(), open.end(),
            [](const Bounded& a, const Bounded& b) { return a.start < b.start; });
  return open;
}

void exact_cycle(DpDriver& driver, int rows, const std::vector<std::vector<std::int32_t>>& valid,
                 const std::vector<std::int32_t>& first_row,
                 const std::vector<std::vector<std::int64_t>>& root_costs,
                 std::vector<Bounded> open, CycleSearch& search, int& passes) {
  const std::size_t N = valid.size();
  // Bounds (none with empty rows): remaining costs after each entry, and through[r][j] = the
  // root pass's cost + remaining, the least cost of any path through entry j of row r. A cycle
  // through start t costs at least its first-row cost + remaining[0].
  const bool bounded = std::none_of(valid.begin(), valid.end(), [](auto& v) { return v.empty(); });
  std::vector<std::vector<std::int64_t>> remaining;
  if (bounded && !open.empty()) {
    remaining = driver.remaining_costs(first_row);
    ++passes;
    for (Bounded& b : open) {
      const auto at = std::lower_bound(first_row.begin(), first_row.end(), b.start);
      const std::size_t e = std::size_t(at - first_row.begin());
      b.bound = std::max(b.bound, root_costs[0][e] + remaining[0][e]);
    }
    std::erase_if(open, [&](const Bounded& b) { return !search.may_win(b.bound, b.start); });
  }
  // The rows of a pass: entries whose least path cost is within the limit (the best cycle's).
  std::int64_t rows_limit = -1;
  std::vector<std::vector<std::int32_t>> kept(N);
  std::vector<std::vector<std::int64_t>> kept_remaining(N);
  auto keep_within = [&](std::int64_t limit) {
    if (limit == rows_limit) return true;
    rows_limit = limit;
    for (std::size_t r = 1; r < N; ++r) {
      kept[r].clear(), kept_remaining[r].clear();
      for (std::size_t j = 0; j < valid[r].size(); ++j) {
        if (root_costs[r][j] > limit - remaining[r][j]) continue;
        kept[r].push_back(valid[r][j]);
        kept_remaining[r].push_back(remaining[r][j]);
      }
      if (kept[r].empty()) return false;  // no path within the limit: no cycle can win
    }
    return true;
  };

  struct Group {
    std::int64_t bound = 0;  // the least bound of its starts
    std::vector<Bounded> starts;
  };
  auto later = [](const Group& a, const Group& b) {
    return a.bound != b.bound ? a.bound > b.bound : a.starts[0].start > b.starts[0].start;
  };
  std::priority_queue<Group, std::vector<Group>, decltype(later)> queue(later);
  auto push_halves = [&](std::vector<Bounded> starts) {
    const auto middle = starts.begin() + std::ptrdiff_t(starts.size() + 1) / 2;
    for (auto [from, to] : {std::pair{starts.begin(), middle}, std::pair{middle, starts.end()}}) {
      if (from == to) continue;
      Group group{kNoCost, std::vector<Bounded>(from, to)};
      for (const Bounded& b : group.starts) group.bound = std::min(group.bound, b.bound);
      queue.push(std::move(group));
    }
  };
  push_halves(std::move(open));
  while (!queue.empty()) {
    Group group = queue.top();
    queue.pop();
    std::erase_if(group.starts,
                  [&](const Bounded& b) { return !search.may_win(b.bound, b.start); });
    if (group.starts.empty()) continue;
    std::vector<std::int32_t> starts;
    for (const Bounded& b : group.starts) starts.push_back(b.start);
    PassOptions options;
    const bool prune = bounded && search.cost != kNoCost;
    if (prune) {
      if (!keep_within(search.cost)) break;
      options.remaining = [&](int r) -> const std::vector<std::int64_t>& {
        return kept_remaining[std::size_t(r)];
      };
      options.limit = search.cost;
    }
    auto row_indices = [&](int r) -> const std::vector<std::int32_t>& {
      if (std::size_t(r) >= N) return starts;
      return prune && r > 0 ? kept[std::size_t(r)] : valid[std::size_t(r)];
    };
    const Pass pass = driver.forward(starts, rows, row_indices, options);
    ++passes;
    if (!pass.aborted) push_halves(examine(pass, search));
  }
}

}  // namespace tw::detail
