// The pattern objective (docs/synthesis.md, "Objective"): the unary coverage cost against a
// direct count, CPU = OpenCL with it, and the optimum it moves back onto the band.
#include <gtest/gtest.h>

#include <algorithm>

#include "synth/detail/cost.hpp"
#include "synth/detail/coverage_term.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/opencl_backend.hpp"
#include "synth/exemplar_stats.hpp"
#include "synth/shapes.hpp"
#include "synth/synthesize.hpp"
#include "synth_fixtures.hpp"
#include "test_opencl_fixtures.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

int direct_count(const detail::CostTexels& t, const detail::PieceFootprint& piece, int ux, int uy) {
  int opaque = 0;
  for (const auto& o : piece.interior)
    opaque += detail::is_opaque(detail::texel_at(t, ux + o.dx, uy + o.dy));
  return opaque;
}

TEST(CoverageTerm, CostsFollowTheFormulaOnADirectCount) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    std::mt19937 rng(seed);
    const int width = test::uniform(rng, 3, 60), height = test::uniform(rng, 2, 24);
    const int column = test::uniform(rng, 1, 16);
    const detail::CostTexels texels =
        test::random_texels(rng, width, height, test::uniform(rng, 10, 95));
    detail::PieceFootprint piece = test::random_piece(rng, column);
    piece.interior.push_back({1, column / 2});  // never empty
    const detail::PositionSpace space{width, height, column};
    const detail::CoverageTerm term{
        test::uniform(rng, 1, 5000), test::uniform(rng, 0, 256 * height), {}};
    std::vector<std::int32_t> all(std::size_t(space.count()));
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = std::int32_t(i);
    std::vector<std::int64_t> costs;
    std::vector<std::int32_t> counts;
    detail::coverage_costs(texels, space, piece, term, all, costs);
    detail::count_opaque_interior(texels, space, piece, all, counts);
    const int uy_c = detail::centred_row(piece, term);
    std::int64_t sum = 0;
    for (int ux = 0; ux < width; ++ux) sum += direct_count(texels, piece, ux, uy_c);
    const std::int64_t n = std::int64_t(piece.interior.size());
    int charged = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
      const int ux = space.ux(all[i]), uy = space.uy(all[i]);
      const int o = direct_count(texels, piece, ux, uy);
      ASSERT_EQ(counts[i], o) << "seed " << seed;
      const std::int64_t target =
          std::max(sum, std::int64_t(width) * direct_count(texels, piece, ux, uy_c));
      const std::int64_t lost = std::max<std::int64_t>(0, target - std::int64_t(width) * o);
      const std::int64_t expected = std::int64_t(__int128(term.weight_milli) * detail::kGamma *
                                                 column * lost / (__int128(1000) * width * n));
      ASSERT_EQ(costs[i], expected) << "seed " << seed << " at (" << ux << ", " << uy << ")";
      charged += costs[i] > 0;
    }
    EXPECT_GT(charged, 0) << "seed " << seed;
  }
}

class PatternObjectiveBackends : public testing::TestWithParam<const char*> {};

TEST_P(PatternObjectiveBackends, CpuAndOpenClGiveTheSamePlacements) {
  TW_REQUIRE_OPENCL(context);
  const Exemplar chain = test::chain_exemplar(60, 24, 17);
  const Ribbon ribbon = make_ribbon(make_shape(GetParam(), 30.0), {5.0, 2.0});
  const GridSpec canvas = test::canvas_around(ribbon, 0.5, 2.0);
  SynthParams params;
  params.scale = 4.0;
  params.allow_empty_pieces = true;
  auto cpu = detail::make_cpu_backend();
  auto opencl = detail::make_opencl_backend(*context);
  const Synthesis a = detail::synthesize_on(*cpu, chain, ribbon, canvas, nullptr, params);
  const Synthesis b = detail::synthesize_on(*opencl, chain, ribbon, canvas, nullptr, params);
  EXPECT_EQ(a.objective, "pattern");
  EXPECT_GT(a.objective_cost, a.total_cost);  // some unary cost is paid
  EXPECT_EQ(a.objective_cost, b.objective_cost);
  EXPECT_EQ(a.total_cost, b.total_cost);
  EXPECT_EQ(a.valid_counts, b.valid_counts);
  ASSERT_EQ(a.placements.size(), b.placements.size());
  for (std::size_t i = 0; i < a.placements.size(); ++i) {
    EXPECT_EQ(a.placements[i].ux, b.placements[i].ux) << i;
    EXPECT_EQ(a.placements[i].uy, b.placements[i].uy) << i;
    EXPECT_EQ(a.placements[i].empty, b.placements[i].empty) << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Synth, PatternObjectiveBackends,
                         testing::Values("s-curve", "hairpin", "circle"));

TEST(PatternObjective, KeepsTheRidgeBandWhereThePaperCopiesStrayTexels) {
  // The real ridge band has two stray opaque texels above its band: under the paper's rule the
  // optimum holds only them (Omega = 0). The default objective and floor copy the band.
  const Exemplar band =
      load_exemplar((test::source_dir() / "samples/exemplars/ridge_band_200x64.png").string());
  const Ribbon ribbon = make_ribbon(make_shape("s-curve", 400.0), {48.0, 40.0});
  const GridSpec canvas = test::canvas_around(ribbon, 1.0, 4.0);
  auto cpu = detail::make_cpu_backend();
  SynthParams paper;
  paper.scale = 1.0;
  paper.objective = Objective::paper;
  paper.min_coverage = 0.0;
  SynthParams pattern;
  pattern.scale = 1.0;
  const Synthesis p = detail::synthesize_on(*cpu, band, ribbon, canvas, nullptr, paper);
  const Synthesis q = detail::synthesize_on(*cpu, band, ribbon, canvas, nullptr, pattern);
  std::printf("ridge band: paper coverage ratio %.3f (Omega %lld), pattern %.3f (Omega %lld)\n",
              p.coverage_ratio, (long long)p.total_cost, q.coverage_ratio, (long long)q.total_cost);
  EXPECT_EQ(p.total_cost, 0);
  EXPECT_LT(p.coverage_ratio, 0.05);
  EXPECT_GE(q.coverage_ratio, 0.9);
  EXPECT_TRUE(q.min_coverage_from_exemplar);
  EXPECT_NEAR(q.min_coverage, kCoverageFloorOfNatural * q.natural_coverage, 0.05);
  EXPECT_GT(q.min_coverage, 0.0);
  EXPECT_GT(q.objective_cost, q.total_cost);
}

}  // namespace
}  // namespace tw
