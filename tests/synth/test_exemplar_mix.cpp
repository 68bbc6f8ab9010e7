// Several exemplars in one feature (synth/detail/exemplar_mix.hpp): the DP over the atlas of
// two exemplars reaches the optimum of enumerating every sequence of positions drawn from
// both exemplars' own position spaces, with seams measured across exemplars directly from
// the two exemplars' texels; pieces bound to one exemplar only use its positions; CPU and
// OpenCL agree.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <utility>

#include "core/error.hpp"
#include "ribbon/ribbon.hpp"
#include "synth/detail/cost.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/dp.hpp"
#include "synth/detail/exemplar_mix.hpp"
#include "synth/detail/footprint.hpp"
#include "synth/detail/opencl_backend.hpp"
#include "synth_fixtures.hpp"
#include "test_opencl_fixtures.hpp"

namespace tw {
namespace {

using detail::CostTexels;
using detail::PieceFootprint;
using detail::PositionSpace;

// The seam between piece `piece` at position a of exemplar ta and the next piece at position
// b of exemplar tb: the definition of seam_cost, reading each side from its own exemplar.
std::int64_t cross_seam(const CostTexels& ta, const PositionSpace& sa, const PieceFootprint& piece,
                        std::int32_t a, const CostTexels& tb, const PositionSpace& sb,
                        std::int32_t b) {
  const std::int32_t X0 = sa.ux(a) * 256 - 128, Y0 = sa.uy(a) * 256 - 128;
  std::int64_t sum = 0;
  for (int k = 0; k < piece.column; ++k)
    sum += detail::xi(detail::sample_bilinear(ta, X0 + piece.right_fx[k], Y0 + piece.right_fy[k]),
                      detail::texel_at(tb, sb.ux(b), sb.uy(b) + k), ta.binary_alpha);
  return sum;
}

struct MixProblem {
  Exemplar a = test::band_exemplar(9, 6, 2, 3, 5, 4);
  Exemplar b = test::band_exemplar(7, 5, 1, 2, 17, 3);
  std::vector<PieceFootprint> pieces;
  int column = 0;
  MixProblem() {
    const Ribbon ribbon = make_ribbon(Curve{{{0, 0}, {4.6, 0}}, false}, {5.0, 1.6});
    column = detail::column_count(5.0, 1.0);
    for (const Piece& piece : ribbon.pieces)
      pieces.push_back(detail::make_piece_footprint(piece, 1.0, column, GridSpec{}, nullptr));
    pieces.resize(3);
  }
  const CostTexels& texels(int e) const { return e == 0 ? a.cost : b.cost; }
  PositionSpace space(int e) const { return {texels(e).width, texels(e).height, column}; }
};

// Min over every sequence of (exemplar, own position), piece i drawing from allowed[i].
std::int64_t brute_force(const MixProblem& p,
                         const std::vector<std::vector<std::uint8_t>>& allowed) {
  auto cpu = detail::make_cpu_backend();
  std::vector<std::vector<std::pair<int, std::int32_t>>> candidates(p.pieces.size());
  for (std::size_t i = 0; i < p.pieces.size(); ++i)
    for (int e = 0; e < 2; ++e) {
      if (!allowed[i][std::size_t(e)]) continue;
      std::vector<std::uint8_t> flags;
      std::vector<std::int32_t> own;
      cpu->find_valid_positions(p.texels(e), p.space(e), p.pieces[i], flags);
      cpu->compact_valid_positions(flags, own);
      for (std::int32_t v : own) candidates[i].emplace_back(e, v);
    }
  std::int64_t best = std::numeric_limits<std::int64_t>::max();
  std::vector<std::pair<int, std::int32_t>> seq(p.pieces.size());
  std::function<void(std::size_t, std::int64_t)> go = [&](std::size_t i, std::int64_t sum) {
    if (sum >= best) return;
    if (i == p.pieces.size()) {
      best = sum;
      return;
    }
    for (const auto& c : candidates[i]) {
      const std::int64_t seam =
          i == 0
              ? 0
              : cross_seam(p.texels(seq[i - 1].first), p.space(seq[i - 1].first), p.pieces[i - 1],
                           seq[i - 1].second, p.texels(c.first), p.space(c.first), c.second);
      seq[i] = c;
      go(i + 1, sum + seam);
    }
  };
  go(0, 0);
  return best;
}

TEST(ExemplarMix, DpOverTheAtlasIsTheOptimumOverBothExemplars) {
  const MixProblem p;
  const detail::ExemplarMix mix =
      detail::make_exemplar_mix({&p.a.cost, &p.b.cost}, detail::mix_gap(p.pieces));
  const PositionSpace space = mix.space(p.column);
  EXPECT_EQ(mix.x0, (std::vector<int>{0, 9 + detail::mix_gap(p.pieces)}));
  const std::vector<std::vector<std::vector<std::uint8_t>>> bindings = {
      {{1, 1}, {1, 1}, {1, 1}},  // free mix
      {{1, 0}, {1, 1}, {0, 1}},  // a stretch of A, then one of B: a switch is forced
      {{0, 1}, {0, 1}, {0, 1}},  // B only
  };
  TW_REQUIRE_OPENCL(context);
  auto cpu = detail::make_cpu_backend();
  auto opencl = detail::make_opencl_backend(*context);
  for (std::size_t k = 0; k < bindings.size(); ++k) {
    SCOPED_TRACE(testing::Message() << "binding " << k);
    const auto& allowed = bindings[k];
    detail::DpInput input;
    input.texels = &mix.atlas;
    input.space = space;
    input.pieces = p.pieces;
    input.keep_positions = [&](int piece, std::vector<std::int32_t>& indices) {
      detail::keep_exemplars(mix, space, allowed[std::size_t(piece)], indices);
    };
    const detail::DpResult r = detail::run_dp(*cpu, input);
    const std::int64_t best = brute_force(p, allowed);
    for (int count : r.valid_counts) ASSERT_GT(count, 3);
    EXPECT_GT(best, 0);
    EXPECT_EQ(r.total_cost, best);
    const detail::DpResult cl = detail::run_dp(*opencl, input);
    EXPECT_EQ(cl.total_cost, r.total_cost);
    EXPECT_EQ(cl.positions, r.positions);
    for (std::size_t i = 0; i < r.positions.size(); ++i) {
      const int e = detail::exemplar_of(mix, space, r.positions[i]);
      ASSERT_GE(e, 0);
      EXPECT_TRUE(allowed[i][std::size_t(e)]) << "piece " << i << " uses exemplar " << e;
    }
    // The atlas table holds exactly the union of both exemplars' own valid positions.
    std::size_t own_total = 0;
    for (int e = 0; e < 2; ++e) {
      if (!allowed[0][std::size_t(e)]) continue;
      std::vector<std::uint8_t> flags;
      std::vector<std::int32_t> own;
      cpu->find_valid_positions(p.texels(e), p.space(e), p.pieces[0], flags);
      cpu->compact_valid_positions(flags, own);
      own_total += own.size();
    }
    EXPECT_EQ(std::size_t(r.valid_counts[0]), own_total);
    if (k == 1) {
      EXPECT_EQ(detail::exemplar_of(mix, space, r.positions.front()), 0);
      EXPECT_EQ(detail::exemplar_of(mix, space, r.positions.back()), 1);
    }
  }
}

TEST(ExemplarMix, GapsAndShortExemplarsAreNoPositions) {
  const MixProblem p;
  const detail::ExemplarMix mix = detail::make_exemplar_mix({&p.a.cost, &p.b.cost}, 5);
  const PositionSpace space = mix.space(3);
  EXPECT_EQ(mix.atlas.width, 9 + 5 + 7);
  EXPECT_EQ(mix.atlas.height, 6);
  EXPECT_EQ(detail::exemplar_of(mix, space, (0 + 3) * space.width + 8), 0);    // (8, 0)
  EXPECT_EQ(detail::exemplar_of(mix, space, (0 + 3) * space.width + 9), -1);   // the gap
  EXPECT_EQ(detail::exemplar_of(mix, space, (0 + 3) * space.width + 14), 1);   // B's column 0
  EXPECT_EQ(detail::exemplar_of(mix, space, (5 + 3) * space.width + 14), -1);  // below B (H = 5)
  EXPECT_EQ(detail::exemplar_of(mix, space, (5 + 3) * space.width + 2), 0);    // A has row 5
  EXPECT_EQ(mix.atlas.rgba[std::size_t(2) * 21 + 14], p.b.cost.rgba[std::size_t(2) * 7]);
  CostTexels continuous = p.b.cost;
  continuous.binary_alpha = false;
  EXPECT_THROW(detail::make_exemplar_mix({&p.a.cost, &continuous}, 5), Error);
}

}  // namespace
}  // namespace tw
