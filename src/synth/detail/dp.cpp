#include "synth/detail/dp.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/progress.hpp"
#include "core/split_mix.hpp"
#include "synth/detail/closed_cycle.hpp"
#include "synth/detail/cost.hpp"
#include "synth/detail/dp_driver.hpp"

namespace tw::detail {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
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
  DpDriver driver(backend, input, result.timings);
  const auto& valid = driver.valid_positions();
  for (const auto& v : valid) result.valid_counts.push_back(int(v.size()));

  std::vector<std::int32_t> first_row = valid[0];
  if (input.first_index) {
    if (!std::binary_search(valid[0].begin(), valid[0].end(), *input.first_index))
      fail("the fixed first position ({}, {}) is not a valid position for piece 0",
           input.space.ux(*input.first_index), input.space.uy(*input.first_index));
    first_row = {*input.first_index};
  } else if (input.seed != 0 && !valid[0].empty()) {
    first_row = {valid[0][split_mix64(input.seed) % valid[0].size()]};
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
  // Closed curves keep the costs of every row: the exact mode's bounds (exact_cycle).
  std::vector<std::vector<std::int64_t>> root_costs;
  PassOptions options;
  options.progress = progress.get();
  if (input.closed) options.record = &root_costs;
  const Pass pass = driver.forward(first_row, rows, free_rows(first_row), options);

  auto start = Clock::now();
  if (!input.closed) {
    const std::int32_t entry = pass.rows.back().empty ? 0 : best_entry(pass.last_cost);
    result.positions = backtrack(pass, entry);
    result.total_cost = pass.last_cost[std::size_t(entry)];
    result.timings.backtrack_ms += ms_since(start);
    return result;
  }

  // Closed: the terminal row N stands for piece 0 again; a cycle has equal first and terminal
  // positions. The approximation (the paper's): backtrack from terminal entries in increasing
  // (cost, entry) and keep the first cycle; `examine` does it and keeps the starts that the
  // exact mode must still look at.
  const Row& terminal = pass.rows.back();
  if (terminal.empty) fail("closed curve: piece 0 has no valid position to close the cycle");
  CycleSearch search;
  std::vector<Bounded> open = examine(pass, search);
  result.approximate_cycle_cost = search.cost == kNoCost ? -1 : search.cost;
  result.timings.backtrack_ms += ms_since(start);
  if (!input.exact_cycle && search.cost != kNoCost) {
    result.total_cost = search.cost;
    result.positions = std::move(search.positions);
    return result;
  }
  if (!input.exact_cycle)
    logger().info(
        "closed curve: the single-DP approximation found no cycle; running the exact mode");
  exact_cycle(driver, rows, valid, first_row, root_costs, std::move(open), search,
              result.exact_dp_passes);
  if (search.cost == kNoCost) fail("closed curve: no cycle of valid positions exists");
  result.total_cost = search.cost;
  result.positions = std::move(search.positions);
  return result;
}

}  // namespace tw::detail
