// The pruned DP row equals the naive one, and the pruning bound never exceeds the true D.
#include <gtest/gtest.h>

#include <random>

#include "synth/detail/cost.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/edge_bound.hpp"

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
        EXPECT_LE(std::int64_t(edge_cost_bound(sa, i, sb, j, binary)), d);
      }
    }
  }
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

}  // namespace
}  // namespace tw::detail
