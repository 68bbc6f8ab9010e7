// Several exemplars in one feature (synth/detail/exemplar_mix.hpp): the DP over the atlas of
// two exemplars reaches the optimum of enumerating every sequence of positions drawn from
// both exemplars' own position spaces, with seams measured across exemplars directly from
// the two exemplars' texels; pieces bound to one exemplar only use its positions; CPU and
// OpenCL agree.
#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <limits>
#include <random>
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

// Min over every sequence of (exemplar, own position), piece i drawing from allowed[i], of the
// seams plus `switch_cost` per change of exemplar.
std::int64_t brute_force(const MixProblem& p, const std::vector<std::vector<std::uint8_t>>& allowed,
                         std::int64_t switch_cost) {
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
                           seq[i - 1].second, p.texels(c.first), p.space(c.first), c.second) +
                    (seq[i - 1].first != c.first ? switch_cost : 0);
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
  EXPECT_EQ(mix.layout.x0, (std::vector<int>{0, 9 + detail::mix_gap(p.pieces)}));
  const std::vector<std::vector<std::vector<std::uint8_t>>> bindings = {
      {{1, 1}, {1, 1}, {1, 1}},  // free mix
      {{1, 0}, {1, 1}, {0, 1}},  // a stretch of A, then one of B: a switch is forced
      {{0, 1}, {0, 1}, {0, 1}},  // B only
  };
  TW_REQUIRE_OPENCL(context);
  auto cpu = detail::make_cpu_backend();
  auto opencl = detail::make_opencl_backend(*context);
  // 0: a change of exemplar costs its seam only; 40 colour units: less than the free mix's
  // gain at some seams; 8 gamma: more than any seam
  // of 5 samples can gain.
  for (const std::int64_t switch_cost : {std::int64_t(0), std::int64_t(40) * detail::kColourScale,
                                         std::int64_t(8) * detail::kGamma}) {
    for (std::size_t k = 0; k < bindings.size(); ++k) {
      SCOPED_TRACE(testing::Message() << "binding " << k << ", switch cost " << switch_cost);
      const auto& allowed = bindings[k];
      detail::DpInput input;
      input.texels = &mix.atlas;
      input.space = space;
      input.pieces = p.pieces;
      input.keep_positions = [&](int piece, std::vector<std::int32_t>& indices) {
        detail::keep_exemplars(mix.layout, space, allowed[std::size_t(piece)], indices);
      };
      input.exemplar_switch.cost = switch_cost;
      input.exemplar_switch.exemplar = [&](std::int32_t index) {
        return detail::exemplar_of(mix.layout, space, index);
      };
      const detail::DpResult r = detail::run_dp(*cpu, input);
      const std::int64_t best = brute_force(p, allowed, switch_cost);
      for (int count : r.valid_counts) ASSERT_GT(count, 3);
      EXPECT_GT(best, 0);
      EXPECT_EQ(r.total_cost, best);
      EXPECT_EQ(detail::objective_cost(mix.atlas, space, p.pieces, r.positions, false, {},
                                       input.exemplar_switch),
                r.total_cost);
      const detail::DpResult cl = detail::run_dp(*opencl, input);
      EXPECT_EQ(cl.total_cost, r.total_cost);
      EXPECT_EQ(cl.positions, r.positions);
      for (std::size_t i = 0; i < r.positions.size(); ++i) {
        const int e = detail::exemplar_of(mix.layout, space, r.positions[i]);
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
      const int switches =
          detail::exemplar_switches(r.positions, false, input.exemplar_switch.exemplar);
      if (k == 1) {
        EXPECT_EQ(detail::exemplar_of(mix.layout, space, r.positions.front()), 0);
        EXPECT_EQ(detail::exemplar_of(mix.layout, space, r.positions.back()), 1);
        EXPECT_GE(switches, 1);
      }
      if (k == 0 && switch_cost == 0) {
        EXPECT_GT(switches, 0) << "the free mix seams best mixed";
      }
      if (k == 0 && switch_cost == 8 * detail::kGamma) {
        EXPECT_EQ(switches, 0);
      }
    }
  }
}

// Columns first .. first + count - 1 (modulo 30) of a band of 30 random colours on rows 1..3.
Exemplar cyclic_band_stretch(int first, int count) {
  constexpr int kPeriod = 30, kHeight = 6;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.1f, 0.9f);
  std::vector<std::array<float, 3>> colours(kPeriod);
  for (auto& c : colours) c = {u(rng), u(rng), u(rng)};
  std::vector<float> t(std::size_t(count) * kHeight * 4, 0.0f);
  for (int x = 0; x < count; ++x)
    for (int y = 1; y <= 3; ++y) {
      const auto& c = colours[std::size_t((first + x) % kPeriod)];
      float* p = t.data() + (std::size_t(y) * count + x) * 4;
      p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 1.0f;
    }
  return make_exemplar(count, kHeight, {"R", "G", "B", "A"}, std::move(t), "stretch(test)");
}

// The optimum under a larger switching cost never switches more: for s1 < s2 and optima x1, x2,
// Omega1 + s1 k1 <= Omega2 + s1 k2 and Omega2 + s2 k2 <= Omega1 + s2 k1 give k2 <= k1.
TEST(ExemplarMix, SwitchCostReducesSwitchesMonotonically) {
  // Two stretches of one cyclic band of random columns, each holding the other's ends: alone,
  // an exemplar runs out and must jump to a column that seams badly; mixed, every run goes on
  // in the other exemplar for free.
  const Exemplar a = cyclic_band_stretch(0, 18);
  const Exemplar b = cyclic_band_stretch(15, 18);
  const Ribbon ribbon = make_ribbon(Curve{{{0, 0}, {48, 0}}, false}, {5.0, 2.0});
  const int column = detail::column_count(5.0, 1.0);
  std::vector<PieceFootprint> pieces;
  for (const Piece& piece : ribbon.pieces)
    pieces.push_back(detail::make_piece_footprint(piece, 1.0, column, GridSpec{}, nullptr));
  const detail::ExemplarMix mix =
      detail::make_exemplar_mix({&a.cost, &b.cost}, detail::mix_gap(pieces));
  const PositionSpace space = mix.space(column);
  auto cpu = detail::make_cpu_backend();
  detail::DpInput input;
  input.texels = &mix.atlas;
  input.space = space;
  input.pieces = pieces;
  input.keep_positions = [&](int, std::vector<std::int32_t>& indices) {
    detail::keep_exemplars(mix.layout, space, {}, indices);
  };
  input.exemplar_switch.exemplar = [&](std::int32_t index) {
    return detail::exemplar_of(mix.layout, space, index);
  };
  std::vector<int> switches;
  std::vector<std::int64_t> omegas;
  for (int colour_units : {0, 4, 8, 16, 32, 64, 1024, 65536}) {
    input.exemplar_switch.cost = std::int64_t(colour_units) * detail::kColourScale;
    const detail::DpResult r = detail::run_dp(*cpu, input);
    switches.push_back(
        detail::exemplar_switches(r.positions, false, input.exemplar_switch.exemplar));
    omegas.push_back(detail::sequence_cost(mix.atlas, space, pieces, r.positions, false));
    EXPECT_EQ(r.total_cost, omegas.back() + input.exemplar_switch.cost * switches.back());
  }
  ASSERT_GE(pieces.size(), 10u);
  EXPECT_GE(switches.front(), 2) << "the free mix uses both exemplars where they seam best";
  EXPECT_EQ(switches.back(), 0);
  for (std::size_t k = 1; k < switches.size(); ++k) {
    EXPECT_LE(switches[k], switches[k - 1]) << "switch cost step " << k;
    EXPECT_GE(omegas[k], omegas[k - 1]) << "fewer switches cost seams";
  }
  EXPECT_GT(omegas.back(), omegas.front());
}

TEST(ExemplarMix, GapsAndShortExemplarsAreNoPositions) {
  const MixProblem p;
  const detail::ExemplarMix mix = detail::make_exemplar_mix({&p.a.cost, &p.b.cost}, 5);
  const PositionSpace space = mix.space(3);
  EXPECT_EQ(mix.atlas.width, 9 + 5 + 7);
  EXPECT_EQ(mix.atlas.height, 6);
  EXPECT_EQ(detail::exemplar_of(mix.layout, space, (0 + 3) * space.width + 8), 0);   // (8, 0)
  EXPECT_EQ(detail::exemplar_of(mix.layout, space, (0 + 3) * space.width + 9), -1);  // the gap
  EXPECT_EQ(detail::exemplar_of(mix.layout, space, (0 + 3) * space.width + 14), 1);  // B's column 0
  EXPECT_EQ(detail::exemplar_of(mix.layout, space, (5 + 3) * space.width + 14),
            -1);  // below B (H = 5)
  EXPECT_EQ(detail::exemplar_of(mix.layout, space, (5 + 3) * space.width + 2), 0);  // A has row 5
  EXPECT_EQ(mix.atlas.rgba[std::size_t(2) * 21 + 14], p.b.cost.rgba[std::size_t(2) * 7]);
  CostTexels continuous = p.b.cost;
  continuous.binary_alpha = false;
  EXPECT_THROW(detail::make_exemplar_mix({&p.a.cost, &continuous}, 5), Error);
}

}  // namespace
}  // namespace tw
