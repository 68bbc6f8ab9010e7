// The pruned DP row equals the naive one, and the pruning bound never exceeds the true D.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <random>

#include "synth/detail/cost.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/edge_bound.hpp"
#include "synth/detail/mask_groups.hpp"

namespace tw::detail {
namespace {

// Random columns that look like a pattern: runs of opaque texels of a few colours.
ColumnSet random_columns(std::mt19937& rng, int count, int C, bool binary) {
  ColumnSet set;
  set.column = C;
  set.binary_alpha = binary;
  std::uniform_int_distribution<int> byte(0, 255), palette(0, 3), run(1, 12);
  const std::uint32_t colours[4] = {pack_rgba(200, 40, 30, 255), pack_rgba(190, 50, 20, 255),
                                    pack_rgba(30, 30, 200, 255), 0u};
  for (int j = 0; j < count; ++j) {
    int k = 0;
    while (k < C) {
      const int length = run(rng);
      std::uint32_t c = colours[palette(rng)];
      if (!binary) c = pack_rgba(byte(rng), byte(rng), byte(rng), byte(rng));
      for (int i = 0; i < length && k < C; ++i, ++k) set.samples.push_back(c);
    }
  }
  return set;
}

TEST(CpuRow, PrunedEqualsNaiveOnRandomRows) {
  for (int seed = 0; seed < 40; ++seed) {
    std::mt19937 rng(seed);
    const bool binary = seed % 4 != 3;
    const int C = 5 + seed % 37;
    const int previous = 50 + seed * 7, current = 40 + seed * 5;
    const ColumnSet right = random_columns(rng, previous, C, binary);
    const ColumnSet left = random_columns(rng, current, C, binary);
    std::vector<std::int64_t> p(static_cast<std::size_t>(previous));
    std::uniform_int_distribution<std::int64_t> spread(0, seed % 2 ? 200000 : 30);
    for (auto& x : p) x = spread(rng);  // small spreads force many ties
    std::vector<std::int64_t> naive_cost, pruned_cost;
    std::vector<std::int32_t> naive_arg, pruned_arg;
    update_table_row_naive(p, right, left, naive_cost, naive_arg);
    std::int64_t evaluated = 0;
    update_table_row_pruned(p, right, left, pruned_cost, pruned_arg, &evaluated);
    ASSERT_EQ(naive_cost, pruned_cost) << "seed " << seed;
    ASSERT_EQ(naive_arg, pruned_arg) << "seed " << seed;
    EXPECT_LE(evaluated, std::int64_t(previous + 2) * current);  // + two early guesses per entry
  }
}

// Long edges (several mask words), wide cost spreads (walks across mask groups), both alphas.
TEST(CpuRow, PrunedEqualsNaiveOnLongEdges) {
  const int columns[] = {63, 64, 65, 90, 128, 130};
  for (int seed = 0; seed < 12; ++seed) {
    std::mt19937 rng(500 + seed);
    const bool binary = seed % 6 != 5;
    const int C = columns[seed % 6];
    const ColumnSet right = random_columns(rng, 300, C, binary);
    const ColumnSet left = random_columns(rng, 200, C, binary);
    std::vector<std::int64_t> p(300);
    std::uniform_int_distribution<std::int64_t> spread(0, seed % 3 == 0 ? 10 : 4 * kGamma);
    for (auto& x : p) x = spread(rng);
    std::vector<std::int64_t> naive_cost, pruned_cost;
    std::vector<std::int32_t> naive_arg, pruned_arg;
    update_table_row_naive(p, right, left, naive_cost, naive_arg);
    update_table_row_pruned(p, right, left, pruned_cost, pruned_arg);
    ASSERT_EQ(naive_cost, pruned_cost) << "seed " << seed;
    ASSERT_EQ(naive_arg, pruned_arg) << "seed " << seed;
  }
}

// Results do not depend on the thread count (tasks start from different neighbour guesses).
TEST(CpuRow, PrunedIsIdenticalOnOneThread) {
  std::mt19937 rng(77);
  const ColumnSet right = random_columns(rng, 400, 90, true);
  const ColumnSet left = random_columns(rng, 300, 90, true);
  std::vector<std::int64_t> p(400);
  std::uniform_int_distribution<std::int64_t> spread(0, 3 * kGamma);
  for (auto& x : p) x = spread(rng);
  std::vector<std::int64_t> many_cost, one_cost;
  std::vector<std::int32_t> many_arg, one_arg;
  update_table_row_pruned(p, right, left, many_cost, many_arg);
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    update_table_row_pruned(p, right, left, one_cost, one_arg);
  }
  EXPECT_EQ(many_cost, one_cost);
  EXPECT_EQ(many_arg, one_arg);
}

// The vectorized integer square root gives colour_term for every reachable squared distance,
// and the capped D is exact up to the limit and above it past the limit.
TEST(CpuRow, CappedEdgeCostIsExact) {
  std::vector<bool> reachable(3 * 255 * 255 + 1, false);
  for (int r = 0; r < 256; ++r)
    for (int g = 0; g < 256; ++g)
      for (int b = 0; b < 256; ++b) reachable[std::size_t(r * r + g * g + b * b)] = true;
  int checked = 0;
  std::vector<std::uint32_t> right, left;
  std::int64_t expected = 0;
  for (int r = 0; r < 256; ++r)
    for (int g = 0; g <= r; ++g)
      for (int b = 0; b <= g; ++b) {
        const int d2 = r * r + g * g + b * b;
        if (!reachable[std::size_t(d2)]) continue;
        reachable[std::size_t(d2)] = false;  // once per d2
        const std::uint32_t p = pack_rgba(255, 255, 255, 255),
                            q = pack_rgba(255 - r, 255 - g, 255 - b, 255);
        ASSERT_EQ(edge_cost_capped(&p, &q, 1, true, kGamma), colour_term(p, q)) << d2;
        // 16 at a time through the vector path: every error would add up (never cancel).
        right.push_back(p);
        left.push_back(q);
        expected += colour_term(p, q);
        if (right.size() == 16) {
          ASSERT_EQ(edge_cost_capped(right.data(), left.data(), 16, true, INT64_MAX), expected);
          right.clear(), left.clear(), expected = 0;
        }
        ++checked;
      }
  EXPECT_GT(checked, 100000);
  std::mt19937 rng(9);
  for (bool binary : {true, false}) {
    const ColumnSet a = random_columns(rng, 50, 90, binary),
                    b = random_columns(rng, 50, 90, binary);
    for (int i = 0; i < 50; ++i) {
      const std::uint32_t* x = a.samples.data() + i * 90;
      const std::uint32_t* y = b.samples.data() + i * 90;
      const std::int64_t d = edge_cost(x, y, 90, binary);
      EXPECT_EQ(edge_cost_capped(x, y, 90, binary, d), d);
      EXPECT_EQ(edge_cost_capped(x, y, 90, binary, INT64_MAX), d);
      if (d > 0) {
        EXPECT_GT(edge_cost_capped(x, y, 90, binary, d - 1), d - 1);
      }
    }
  }
}

TEST(CpuRow, BoundNeverExceedsTrueCost) {
  for (int seed = 0; seed < 20; ++seed) {
    std::mt19937 rng(100 + seed);
    const bool binary = seed % 3 != 0;
    const int C = 3 + seed * 5;
    const ColumnSet a = random_columns(rng, 60, C, binary);
    const ColumnSet b = random_columns(rng, 60, C, binary);
    const EdgeStats sa = make_edge_stats(a), sb = make_edge_stats(b);
    for (int i = 0; i < 60; ++i) {
      for (int j = 0; j < 60; ++j) {
        const std::int64_t d =
            edge_cost(a.samples.data() + i * C, b.samples.data() + j * C, C, binary);
        EXPECT_LE(edge_cost_bound(sa, i, sb, j, binary), d);
        EXPECT_LE(std::int64_t(std::floor(block_colour_bound(sa, i, sb, j))), d);
        const int m = mismatched_samples(sa, i, sb, j);
        EXPECT_FALSE(whole_edge_bound_exceeds(sa, i, sb, j, m, d)) << i << " " << j;
        EXPECT_LE(mismatch_cost(binary) * m, d);
      }
    }
  }
}

// The per-mismatch constants of continuous alpha hold for every pair of alphas on either side
// of 0.5, at the colour terms where they are tightest (0 and the largest).
TEST(CpuRow, ContinuousMismatchBoundsHoldForEveryAlphaPair) {
  EXPECT_EQ(mismatch_cost(false), 8192);
  EXPECT_EQ(mismatch_extra(false), 4659);
  int checked = 0;
  for (std::uint32_t a = 128; a < 256; ++a)
    for (std::uint32_t b = 0; b < 128; ++b)
      for (const auto& [p, q] : {std::pair{pack_rgba(0, 0, 0, a), pack_rgba(0, 0, 0, b)},
                                 std::pair{pack_rgba(255, 255, 255, a), pack_rgba(0, 0, 0, b)},
                                 std::pair{pack_rgba(0, 0, 0, b), pack_rgba(255, 255, 255, a)}}) {
        const std::int64_t x = xi(p, q, false);
        ASSERT_GE(x, mismatch_cost(false)) << a << " " << b;
        ASSERT_GE(x, colour_term(p, q) + mismatch_extra(false)) << a << " " << b;
        ++checked;
      }
  EXPECT_EQ(checked, 128 * 128 * 3);
}

TEST(CpuRow, XiIsTheFlooredScaledDistance) {
  const std::uint32_t p = pack_rgba(10, 20, 30, 255), q = pack_rgba(13, 24, 30, 255);
  EXPECT_EQ(xi(p, q, true), 80);  // 16 * 5
  EXPECT_EQ(xi(p, pack_rgba(10, 20, 30, 0), true), kGamma);
  EXPECT_EQ(xi(pack_rgba(0, 0, 0, 0), pack_rgba(1, 1, 0, 0), true), 22);  // floor(16 * 1.414)
  EXPECT_EQ(colour_term(pack_rgba(0, 0, 0, 255), pack_rgba(255, 255, 255, 255)), kMaxColourTerm);
  // Continuous alpha: half transparent against opaque mixes gamma and colour.
  EXPECT_EQ(xi(pack_rgba(0, 0, 0, 255), pack_rgba(0, 0, 0, 0), false), kGamma);
  EXPECT_EQ(xi(pack_rgba(0, 0, 0, 255), pack_rgba(0, 0, 0, 255), false), 0);
}

TEST(CpuRow, BilinearReadsTexelCentresExactlyAndBlendsBetween) {
  CostTexels t;
  t.width = 2;
  t.height = 1;
  t.rgba = {pack_rgba(0, 0, 0, 255), pack_rgba(200, 100, 50, 255)};
  EXPECT_EQ(sample_bilinear(t, 0, 0), t.rgba[0]);
  EXPECT_EQ(sample_bilinear(t, 256, 0), t.rgba[1]);
  EXPECT_EQ(sample_bilinear(t, 128, 0), pack_rgba(100, 50, 25, 255));
  EXPECT_EQ(sample_bilinear(t, -256, 0), 0u);  // outside: transparent black
}

// The visiting order of the pruned row, built in two halves (the masks' runs, then the costs):
// groups in increasing lowest P, members in increasing (P, v), look-ups by mask.
TEST(CpuRow, MaskGroupsOrderRunsByLowestCostAndMembersByCostThenPosition) {
  const std::vector<std::uint64_t> masks = {0b01, 0b10, 0b01, 0b11, 0b10, 0b01};
  const std::vector<std::int64_t> cost = {5, 3, 5, 9, 1, 2};
  const MaskRuns runs = mask_runs(masks.data(), 6, 1);
  EXPECT_EQ(runs.run_of, (std::vector<std::int32_t>{0, 1, 0, 2, 1, 0}));
  EXPECT_EQ(runs.run_size, (std::vector<std::int32_t>{3, 2, 1}));
  const std::uint64_t absent = 0b100, none = 0;
  EXPECT_EQ(run_with_mask(runs, &masks[3]), 2);
  EXPECT_EQ(run_with_mask(runs, &absent), -1);
  EXPECT_EQ(run_with_mask(runs, &none), -1);

  const MaskGroups groups = group_by_mask(cost, masks.data(), 1);
  EXPECT_EQ(groups.position, (std::vector<std::int32_t>{4, 1, 5, 0, 2, 3}));
  EXPECT_EQ(groups.group_begin, (std::vector<std::int32_t>{0, 2, 5, 6}));
  EXPECT_EQ(groups.group_masks, (std::vector<std::uint64_t>{0b10, 0b01, 0b11}));
  EXPECT_EQ(groups.groups_by_mask, (std::vector<std::int32_t>{1, 0, 2}));
  EXPECT_EQ(group_with_mask(groups, &masks[0]), 1);
  EXPECT_EQ(group_with_mask(groups, &absent), -1);
  const MaskGroups from_runs = group_runs_by_cost(runs, cost);
  EXPECT_EQ(from_runs.position, groups.position);
  EXPECT_EQ(from_runs.group_begin, groups.group_begin);

  // Two words per mask compare word by word, the first word first.
  const std::vector<std::uint64_t> wide = {1, 0, 0, 5, 1, 0};
  const MaskRuns wide_runs = mask_runs(wide.data(), 3, 2);
  EXPECT_EQ(wide_runs.run_of, (std::vector<std::int32_t>{1, 0, 1}));
  EXPECT_EQ(run_with_mask(wide_runs, &wide[2]), 0);
}

}  // namespace
}  // namespace tw::detail
