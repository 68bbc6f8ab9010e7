// The pruned row is exact under the pattern objective and the coverage floor: whole syntheses
// on random small instances give the same placements and costs with the pruned rows and with
// the exhaustive ones (every pair, every sample), on the CPU and on OpenCL; rows whose previous
// costs spread like the unary term's (many groups, bests far above the lowest P) equal the
// definition; the group scan's vector and scalar paths equal its formula; the opaque-interior
// counter equals a direct count whichever runs it picks.
#include <gtest/gtest.h>

#include <bit>
#include <memory>
#include <random>

#include "synth/detail/cost.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/edge_bound.hpp"
#include "synth/detail/forwarding_backend.hpp"
#include "synth/detail/group_scan.hpp"
#include "synth/detail/opaque_count.hpp"
#include "synth/detail/opencl_backend.hpp"
#include "synth/shapes.hpp"
#include "synth/synthesize.hpp"
#include "synth_fixtures.hpp"
#include "test_opencl_fixtures.hpp"

namespace tw::test {
namespace {

// The CPU backend with the exhaustive row update (the definition) instead of the pruned one.
class ExhaustiveCpuBackend final : public detail::ForwardingBackend {
 public:
  std::string name() const override { return "cpu (exhaustive rows)"; }
  void update_table_row(const std::vector<std::int64_t>& previous, const detail::ColumnSet& right,
                        const detail::ColumnSet& left, std::vector<std::int64_t>& cost,
                        std::vector<std::int32_t>& argmin) override {
    detail::update_table_row_naive(previous, right, left, cost, argmin);
  }
};

// A band of random colours (rows row0..row1) with stray opaque texels above and below it, as
// real exemplars have: the floor removes the windows holding only strays, the unary term
// spreads the costs of the rest.
Exemplar band_with_strays(std::mt19937& rng, int W, int H) {
  const int row0 = uniform(rng, 3, H / 2 - 2), row1 = uniform(rng, H / 2, H - 4);
  std::vector<float> t(std::size_t(W) * H * 4, 0.0f);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const bool band = y >= row0 && y <= row1 && uniform(rng, 0, 9) > 0;
      const bool stray = uniform(rng, 0, 99) < 3;
      if (!band && !stray) continue;
      float* p = t.data() + (std::size_t(y) * W + x) * 4;
      p[0] = float(uniform(rng, 10, 240)) / 255.0f, p[1] = float(uniform(rng, 10, 240)) / 255.0f;
      p[2] = float(uniform(rng, 10, 240)) / 255.0f, p[3] = 1.0f;
    }
  return make_exemplar(W, H, {"R", "G", "B", "A"}, std::move(t), "band with strays (test)");
}

void expect_same(const Synthesis& a, const Synthesis& b, const std::string& what) {
  ASSERT_EQ(a.placements.size(), b.placements.size()) << what;
  for (std::size_t i = 0; i < a.placements.size(); ++i) {
    EXPECT_EQ(a.placements[i].empty, b.placements[i].empty) << what << " piece " << i;
    EXPECT_EQ(a.placements[i].ux, b.placements[i].ux) << what << " piece " << i;
    EXPECT_EQ(a.placements[i].uy, b.placements[i].uy) << what << " piece " << i;
  }
  EXPECT_EQ(a.objective_cost, b.objective_cost) << what;
  EXPECT_EQ(a.total_cost, b.total_cost) << what;
  EXPECT_EQ(a.valid_counts, b.valid_counts) << what;
}

TEST(PrunedDp, PatternObjectiveWithFloorEqualsExhaustiveRowsOnBothBackends) {
  TW_REQUIRE_OPENCL(context);
  auto cpu = detail::make_cpu_backend();
  ExhaustiveCpuBackend exhaustive;
  detail::OpenCLBackend opencl(*context);
  detail::OpenCLBackend opencl_exhaustive(*context, {16, 4, false});
  const char* shapes[] = {"s-curve", "arc"};
  int floors = 0, changed = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937 rng(seed);
    const Exemplar exemplar =
        seed % 2 == 1 ? band_with_strays(rng, uniform(rng, 36, 56), uniform(rng, 14, 20))
                      : chain_exemplar(uniform(rng, 40, 56), 18, uniform(rng, 12, 20));
    const double width = uniform(rng, 10, 16), delta = uniform(rng, 3, 6);
    const Ribbon ribbon =
        make_ribbon(make_shape(shapes[seed % 2], (6.0 + seed % 3) * delta), {width, delta});
    const GridSpec canvas = test::canvas_around(ribbon, 1.0, 4.0);
    SynthParams params;
    params.scale = 1.0;
    params.allow_empty_pieces = true;
    params.coverage_weight = 0.5 * uniform(rng, 1, 8);
    const std::string what = "seed " + std::to_string(seed);
    const Synthesis pruned = detail::synthesize_on(*cpu, exemplar, ribbon, canvas, nullptr, params);
    ASSERT_EQ(pruned.objective, "pattern");
    ASSERT_GE(pruned.placements.size(), 5u) << what;
    for (int count : pruned.valid_counts) ASSERT_GE(count, 20) << what;
    floors += pruned.min_coverage > 0.0;
    expect_same(pruned,
                detail::synthesize_on(exhaustive, exemplar, ribbon, canvas, nullptr, params),
                what + " cpu exhaustive");
    expect_same(pruned, detail::synthesize_on(opencl, exemplar, ribbon, canvas, nullptr, params),
                what + " opencl");
    expect_same(pruned,
                detail::synthesize_on(opencl_exhaustive, exemplar, ribbon, canvas, nullptr, params),
                what + " opencl exhaustive");
    params.objective = Objective::paper;
    const Synthesis paper = detail::synthesize_on(*cpu, exemplar, ribbon, canvas, nullptr, params);
    changed += paper.objective_cost != pruned.objective_cost;
    std::printf("%s: %zu pieces, floor %.3f, valid %d..%d, objective %lld (paper %lld)\n",
                what.c_str(), pruned.placements.size(), pruned.min_coverage,
                *std::min_element(pruned.valid_counts.begin(), pruned.valid_counts.end()),
                *std::max_element(pruned.valid_counts.begin(), pruned.valid_counts.end()),
                (long long)pruned.objective_cost, (long long)paper.objective_cost);
  }
  EXPECT_EQ(floors, 8);   // the coverage floor was on in every instance
  EXPECT_GT(changed, 0);  // and the unary term did change some optimum
}

// Random columns with previous costs P = a seam-like part + a unary-like part of up to C
// mismatches: hundreds of mask groups (several 64-group blocks of the scan) and bests many
// mismatches above the lowest P, as under the pattern objective.
TEST(PrunedRow, UnarySpreadCostsEqualTheDefinitionOnBothBackends) {
  TW_REQUIRE_OPENCL(context);
  detail::OpenCLBackend opencl(*context);
  int many_groups = 0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    const int C = uniform(rng, 20, 70), previous = uniform(rng, 200, 500);
    const int current = uniform(rng, 100, 300);
    detail::ColumnSet right{C, {}, true}, left{C, {}, true};
    // Masks from a few runs plus noise, so that groups share some masks and differ in others.
    auto column = [&](detail::ColumnSet& set) {
      const int top = uniform(rng, 0, C / 2), bottom = uniform(rng, top, C);
      for (int k = 0; k < C; ++k) {
        const bool opaque = (k >= top && k < bottom) != (uniform(rng, 0, 19) == 0);
        set.samples.push_back(pack_rgba(uniform(rng, 0, 255), uniform(rng, 0, 255),
                                        uniform(rng, 0, 255), opaque ? 255 : 0));
      }
    };
    for (int v = 0; v < previous; ++v) column(right);
    for (int j = 0; j < current; ++j) column(left);
    std::vector<std::int64_t> P(static_cast<std::size_t>(previous));
    for (auto& p : P)
      p = uniform(rng, 0, 4000) +
          (uniform(rng, 0, 2) == 0 ? 0 : std::int64_t(uniform(rng, 0, C)) * detail::kGamma / 2);
    P[std::size_t(uniform(rng, 0, previous - 1))] = P[0];  // a tie
    std::vector<std::int64_t> expected_cost, cost, cl_cost;
    std::vector<std::int32_t> expected_argmin, argmin, cl_argmin;
    detail::update_table_row_naive(P, right, left, expected_cost, expected_argmin);
    detail::update_table_row_pruned(P, right, left, cost, argmin);
    opencl.update_table_row(P, right, left, cl_cost, cl_argmin);
    EXPECT_EQ(cost, expected_cost) << "seed " << seed;
    EXPECT_EQ(argmin, expected_argmin) << "seed " << seed;
    EXPECT_EQ(cl_cost, expected_cost) << "seed " << seed;
    EXPECT_EQ(cl_argmin, expected_argmin) << "seed " << seed;
    const detail::EdgeStats stats = detail::make_edge_stats(right);
    std::vector<std::vector<std::uint64_t>> masks;
    for (int v = 0; v < previous; ++v)
      masks.emplace_back(stats.masks.begin() + std::ptrdiff_t(v) * stats.words,
                         stats.masks.begin() + std::ptrdiff_t(v + 1) * stats.words);
    std::sort(masks.begin(), masks.end());
    many_groups += std::unique(masks.begin(), masks.end()) - masks.begin() > 128;
  }
  EXPECT_GE(many_groups, 4);
}

TEST(GroupScan, VectorAndScalarPathsEqualTheFormula) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    const int groups = uniform(rng, 1, 300), words = uniform(rng, 1, 3);
    const std::int64_t mismatch =
        seed % 2 ? detail::mismatch_cost(true) : detail::mismatch_cost(false);
    std::vector<std::int64_t> group_min(static_cast<std::size_t>(groups));
    std::int64_t p = 0;
    for (auto& g : group_min) g = p += uniform(rng, 0, 3000);
    std::vector<std::uint64_t> masks(std::size_t(groups) * words);
    for (auto& m : masks) m = std::uint64_t(std::uint32_t(rng())) << 32 | std::uint32_t(rng());
    const detail::GroupScan vector(group_min, masks, words, mismatch);
    const detail::GroupScan scalar(group_min, masks, words, mismatch, false);
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<std::uint64_t> key(static_cast<std::size_t>(words));
      for (int w = 0; w < words; ++w)  // near one group's mask, or anything
        key[std::size_t(w)] =
            trial % 2 ? masks[std::size_t(w)] ^ (std::uint64_t(1) << trial) : std::uint64_t(rng());
      const std::int64_t best = uniform(rng, 0, 2'000'000);
      for (int g0 = 0; g0 < groups; g0 += 64) {
        std::uint64_t expected = 0;
        for (int g = g0; g < std::min(groups, g0 + 64); ++g) {
          int m = 0;
          for (int w = 0; w < words; ++w)
            m += std::popcount(masks[std::size_t(g) * words + w] ^ key[std::size_t(w)]);
          if (group_min[std::size_t(g)] + mismatch * m <= best)
            expected |= std::uint64_t(1) << (g - g0);
        }
        ASSERT_EQ(vector.qualifying(key.data(), g0, best), expected) << "seed " << seed;
        ASSERT_EQ(scalar.qualifying(key.data(), g0, best), expected) << "seed " << seed;
      }
    }
  }
}

TEST(OpaqueCounter, EqualsADirectCountByRowsOrColumns) {
  int by_columns = 0, by_rows = 0;
  for (unsigned seed = 1; seed <= 16; ++seed) {
    std::mt19937 rng(seed);
    const detail::CostTexels texels =
        random_texels(rng, uniform(rng, 3, 40), uniform(rng, 2, 30), uniform(rng, 10, 90));
    const int column = uniform(rng, 2, 24);
    // Tall slanted pieces (fewer column runs), wide ones (fewer row runs), or random offsets.
    detail::PieceFootprint piece =
        seed % 3 == 2 ? random_piece(rng, column) : slanted_piece(column, seed % 3 ? 3 : 30, 0);
    const int row_runs = int(detail::row_runs(piece.interior).size());
    const int column_runs = int(detail::column_runs(piece.interior).size());
    by_columns += column_runs < row_runs, by_rows += row_runs <= column_runs;
    detail::OpaqueCounter counter(texels);
    counter.set_interior(piece.interior);
    for (int uy = -column; uy < texels.height; ++uy)
      for (int ux = 0; ux < texels.width; ++ux) {
        int expected = 0;
        for (const auto& o : piece.interior)
          expected += detail::is_opaque(detail::texel_at(texels, ux + o.dx, uy + o.dy));
        ASSERT_EQ(counter.count(ux, uy), expected) << "seed " << seed << " at " << ux << ", " << uy;
      }
  }
  EXPECT_GT(by_columns, 0);
  EXPECT_GT(by_rows, 0);
}

}  // namespace
}  // namespace tw::test
