// The DP finds the global optimum: compared with enumerating every sequence of valid positions
// on tiny exemplars and ribbons (open and closed).
#include <gtest/gtest.h>

#include <functional>
#include <limits>

#include "synth/detail/cost.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/dp.hpp"
#include "synth/detail/footprint.hpp"
#include "synth/shapes.hpp"
#include "synth_fixtures.hpp"
#include "test_opencl_fixtures.hpp"

namespace tw {
namespace {

struct Problem {
  Exemplar exemplar;
  detail::DpInput input;
  std::vector<std::vector<std::int32_t>> valid;
};

Problem make_problem(const Curve& curve, double width, double delta, double scale, unsigned seed,
                     int gap = 4) {
  Problem p{test::band_exemplar(9, 6, 2, 3, seed, gap), {}, {}};
  const Ribbon ribbon = make_ribbon(curve, {width, delta});
  const int C = detail::column_count(width, scale);
  p.input.texels = &p.exemplar.cost;
  p.input.space = {p.exemplar.width, p.exemplar.height, C};
  p.input.closed = ribbon.closed;
  auto backend = detail::make_cpu_backend();
  for (const Piece& piece : ribbon.pieces) {
    p.input.pieces.push_back(detail::make_piece_footprint(piece, scale, C, GridSpec{}, nullptr));
    std::vector<std::uint8_t> flags;
    backend->find_valid_positions(p.exemplar.cost, p.input.space, p.input.pieces.back(), flags);
    std::vector<std::int32_t> idx;
    backend->compact_valid_positions(flags, idx);
    p.valid.push_back(idx);
  }
  return p;
}

// Minimum of the DP's objective (Omega + unary coverage costs) over all sequences (cycles when
// closed).
std::int64_t brute_force(const Problem& p) {
  const int N = int(p.valid.size());
  // The unary costs of every valid position, each from objective_cost of a one-piece sequence.
  std::vector<std::vector<std::int64_t>> unary(static_cast<std::size_t>(N));
  for (int i = 0; i < N; ++i)
    for (std::int32_t v : p.valid[std::size_t(i)])
      unary[std::size_t(i)].push_back(detail::objective_cost(*p.input.texels, p.input.space,
                                                             {p.input.pieces[std::size_t(i)]}, {v},
                                                             false, p.input.coverage));
  std::vector<std::int32_t> seq(static_cast<std::size_t>(N)), pick(seq.size());
  std::int64_t best = std::numeric_limits<std::int64_t>::max();
  std::function<void(int)> go = [&](int i) {
    if (i == N) {
      std::int64_t cost = detail::sequence_cost(*p.input.texels, p.input.space, p.input.pieces, seq,
                                                p.input.closed);
      for (int k = 0; k < N; ++k) cost += unary[std::size_t(k)][std::size_t(pick[std::size_t(k)])];
      best = std::min(best, cost);
      return;
    }
    for (std::size_t k = 0; k < p.valid[std::size_t(i)].size(); ++k) {
      seq[std::size_t(i)] = p.valid[std::size_t(i)][k];
      pick[std::size_t(i)] = std::int32_t(k);
      go(i + 1);
    }
  };
  go(0);
  return best;
}

TEST(DpBruteForce, OpenCurvesReachTheGlobalOptimum) {
  const Curve straight{{{0, 0}, {6, 0}}, false};
  Curve bent;
  for (int i = 0; i <= 40; ++i) {
    const double a = 0.9 * i / 40.0;
    bent.points.push_back({6 * std::sin(a), 6 - 6 * std::cos(a)});
  }
  int checked = 0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    for (const Curve* curve : std::vector<const Curve*>{&straight, &bent}) {
      Problem p = make_problem(*curve, 5.0, 1.6, 1.0, seed);
      if (p.input.pieces.size() > 4) p.input.pieces.resize(4), p.valid.resize(4);
      auto backend = detail::make_cpu_backend();
      const detail::DpResult r = detail::run_dp(*backend, p.input);
      const std::int64_t best = brute_force(p);
      ASSERT_GT(p.valid[0].size(), 3u);
      EXPECT_EQ(r.total_cost, best) << "seed " << seed;
      // The backtracked placements really cost what the DP says.
      EXPECT_EQ(
          detail::sequence_cost(*p.input.texels, p.input.space, p.input.pieces, r.positions, false),
          r.total_cost);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 12);
}

TEST(DpBruteForce, ClosedCurvesExactModeIsOptimalAndApproximationNoBetter) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    Curve circle;
    for (int i = 0; i < 64; ++i)
      circle.points.push_back({2.0 * std::cos(-i * 0.0982), 2.0 * std::sin(-i * 0.0982)});
    circle.closed = true;
    Problem p = make_problem(circle, 2.0, 3.2, 2.0, seed, 0);  // 4 pieces, C = 4
    ASSERT_EQ(p.input.pieces.size(), 4u);
    auto backend = detail::make_cpu_backend();
    detail::DpInput exact = p.input;
    exact.exact_cycle = true;
    const detail::DpResult e = detail::run_dp(*backend, exact);
    const detail::DpResult a = detail::run_dp(*backend, p.input);
    const std::int64_t best = brute_force(p);
    EXPECT_GT(best, 0);
    EXPECT_EQ(e.total_cost, best) << "seed " << seed;
    EXPECT_GE(a.total_cost, e.total_cost);
    EXPECT_EQ(
        detail::sequence_cost(*p.input.texels, p.input.space, p.input.pieces, e.positions, true),
        e.total_cost);
    std::printf("closed seed %u: exact %lld, approximate %lld (%d exact DP passes)\n", seed,
                (long long)e.total_cost, (long long)a.total_cost, e.exact_dp_passes);
  }
}

// The exact cycle search (branch and bound over sets of starts, with remaining-cost bounds)
// against its definition, one DP per start with piece 0 and the terminal fixed to it: the same
// (cost, lowest start) and the same positions, ties included. Circles over chains and bands of
// a few dozen columns, paper and pattern objectives, cut where the single-DP approximation
// finds no cycle or a worse one.
TEST(DpBruteForce, ExactCycleSearchEqualsOneDpPerStart) {
  int improved = 0, approximation_failed = 0, checked = 0;
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const bool chain = seed % 2 == 1;
    const Exemplar exemplar = chain ? test::chain_exemplar(36 + 4 * int(seed), 20, 12 + int(seed))
                                    : test::band_exemplar(40, 12, 4, 7, seed, 5);
    const double width = chain ? 14.0 : 6.0;
    const Ribbon ribbon = make_ribbon(make_shape("circle", 3.0 * width), {width, 4.0 + seed % 3});
    const int C = detail::column_count(width, 1.0);
    for (const std::int32_t weight : {0, 2000}) {
      detail::DpInput input;
      input.texels = &exemplar.cost;
      input.space = {exemplar.width, exemplar.height, C};
      input.closed = true;
      input.coverage = {weight, chain ? 10 * 256 : 6 * 256, {}};
      for (const Piece& piece : ribbon.pieces)
        input.pieces.push_back(detail::make_piece_footprint(piece, 1.0, C, GridSpec{}, nullptr));
      auto backend = detail::make_cpu_backend();
      const detail::DpResult approximate = detail::run_dp(*backend, input);
      input.exact_cycle = true;
      const detail::DpResult exact = detail::run_dp(*backend, input);
      // The definition: for each start u0, the DP with piece 0 fixed there closes at u0.
      detail::DpInput per_start = input;
      per_start.exact_cycle = false;
      std::int64_t best = std::numeric_limits<std::int64_t>::max();
      std::vector<std::int32_t> positions;
      std::vector<std::uint8_t> valid0;
      backend->find_valid_positions(*input.texels, input.space, input.pieces[0], valid0);
      for (std::int64_t u = 0; u < input.space.count(); ++u) {
        if (!valid0[std::size_t(u)]) continue;
        per_start.first_index = std::int32_t(u);
        const detail::DpResult r = detail::run_dp(*backend, per_start);
        if (r.total_cost < best) best = r.total_cost, positions = r.positions;
      }
      ASSERT_LT(best, std::numeric_limits<std::int64_t>::max());
      EXPECT_EQ(exact.total_cost, best) << "seed " << seed << " weight " << weight;
      EXPECT_EQ(exact.positions, positions) << "seed " << seed << " weight " << weight;
      EXPECT_EQ(detail::objective_cost(*input.texels, input.space, input.pieces, exact.positions,
                                       true, input.coverage),
                exact.total_cost);
      EXPECT_GE(approximate.total_cost, exact.total_cost);
      improved += approximate.total_cost > exact.total_cost;
      approximation_failed += approximate.approximate_cycle_cost < 0;
      ++checked;
      std::printf(
          "seed %u weight %d: %zu pieces, %d valid starts, exact %lld in %d passes, "
          "approximation %lld\n",
          seed, weight, input.pieces.size(), exact.valid_counts[0], (long long)exact.total_cost,
          exact.exact_dp_passes, (long long)approximate.approximate_cycle_cost);
    }
  }
  EXPECT_EQ(checked, 8);
  EXPECT_GE(improved, 4);  // the exact search did work: a better cycle than the approximation's
  EXPECT_GE(approximation_failed, 1);
}

// The pattern objective's unary term (band rows 2..3: centre row 3) keeps the DP exact, open
// and closed, and it changes the optimum on some of these problems.
TEST(DpBruteForce, PatternObjectiveReachesTheGlobalOptimum) {
  const Curve straight{{{0, 0}, {6, 0}}, false};
  Curve circle;
  for (int i = 0; i < 64; ++i)
    circle.points.push_back({2.0 * std::cos(-i * 0.0982), 2.0 * std::sin(-i * 0.0982)});
  circle.closed = true;
  int changed = 0, checked = 0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    for (const std::int32_t weight : {500, 2000, 40000}) {
      const bool closed = seed % 2 == 0;
      Problem p = closed ? make_problem(circle, 2.0, 3.2, 2.0, seed, 0)
                         : make_problem(straight, 5.0, 1.6, 1.0, seed);
      if (p.input.pieces.size() > 4) p.input.pieces.resize(4), p.valid.resize(4);
      auto backend = detail::make_cpu_backend();
      const detail::DpResult paper = detail::run_dp(*backend, p.input);
      p.input.coverage = {weight, 3 * 256, {}};
      p.input.exact_cycle = closed;
      const detail::DpResult r = detail::run_dp(*backend, p.input);
      EXPECT_EQ(r.total_cost, brute_force(p)) << "seed " << seed << " weight " << weight;
      EXPECT_EQ(detail::objective_cost(*p.input.texels, p.input.space, p.input.pieces, r.positions,
                                       closed, p.input.coverage),
                r.total_cost);
      EXPECT_GE(r.total_cost, paper.total_cost);
      changed += r.positions != paper.positions;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 18);
  EXPECT_GT(changed, 0);
}

TEST(DpBruteForce, ValidPositionsOfAStraightPieceOverABand) {
  // Band rows 2..3, C = 5, piece 2 texels long: valid iff the top row (uy) and the bottom-edge
  // row (uy + 5) miss the band and the piece's two columns hold an opaque texel.
  Problem p = make_problem(Curve{{{0, 0}, {4, 0}}, false}, 5.0, 2.0, 1.0, 3);
  const auto& space = p.input.space;
  std::vector<std::int32_t> expected;
  for (std::int64_t i = 0; i < space.count(); ++i) {
    const int ux = space.ux(i), uy = space.uy(i);
    auto band = [](int y) { return y == 2 || y == 3; };
    auto opaque_column = [&](int x) { return x >= 0 && x < 9 && x % 4 != 3; };
    const bool edges_clear =
        !(band(uy) && (opaque_column(ux) || opaque_column(ux + 1) || opaque_column(ux + 2))) &&
        !(band(uy + 5) && (opaque_column(ux) || opaque_column(ux + 1) || opaque_column(ux + 2)));
    const bool holds = uy <= 3 && uy + 4 >= 2 && (opaque_column(ux) || opaque_column(ux + 1));
    if (edges_clear && holds) expected.push_back(std::int32_t(i));
  }
  EXPECT_EQ(p.valid[0], expected);
}

TEST(DpBruteForce, MinimumOpaqueCountIsADirectCount) {
  // The CPU backend's bit-parallel test and prefix-sum count against counting every interior
  // texel of every position (offsets in any order, duplicates counted twice).
  auto backend = detail::make_cpu_backend();
  for (unsigned seed = 1; seed <= 12; ++seed) {
    std::mt19937 rng(seed);
    const int width = test::uniform(rng, 3, 140), height = test::uniform(rng, 2, 30);
    const int column = test::uniform(rng, 1, 30);
    const detail::CostTexels texels =
        test::random_texels(rng, width, height, test::uniform(rng, 10, 95));
    detail::PieceFootprint piece = test::random_piece(rng, column);
    if (seed % 3 == 0) {  // a solid rectangle, sorted as the footprints make them
      piece.interior.clear();
      for (int dy = 0; dy < column; ++dy)
        for (int dx = 0; dx < 9; ++dx) piece.interior.push_back({dx, dy});
    }
    if (seed % 2 == 0) piece.must_be_clear.clear();  // more positions open to the count
    piece.min_opaque = test::uniform(rng, 1, int(piece.interior.size()) * 3 / 4 + 2);
    const detail::PositionSpace space{width, height, column};
    std::vector<std::uint8_t> flags;
    backend->find_valid_positions(texels, space, piece, flags);
    std::int64_t valid = 0;
    for (std::int64_t i = 0; i < space.count(); ++i) {
      const int ux = space.ux(i), uy = space.uy(i);
      bool clear = true;
      for (const auto& o : piece.must_be_clear)
        clear = clear && !detail::is_opaque(detail::texel_at(texels, ux + o.dx, uy + o.dy));
      int opaque = 0;
      for (const auto& o : piece.interior)
        opaque += detail::is_opaque(detail::texel_at(texels, ux + o.dx, uy + o.dy));
      const bool expected = clear && opaque >= piece.min_opaque;
      valid += expected;
      ASSERT_EQ(flags[std::size_t(i)], expected ? 1 : 0)
          << "seed " << seed << " position (" << ux << ", " << uy << ") opaque " << opaque
          << " of min " << piece.min_opaque;
    }
    std::printf("seed %u: %lld of %lld positions valid with min_opaque %d\n", seed,
                (long long)valid, (long long)space.count(), piece.min_opaque);
  }
}

}  // namespace
}  // namespace tw
