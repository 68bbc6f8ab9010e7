// synthesize() end to end on generated chains: avoidance, seams vs the parametric baseline,
// stitching, determinism, placements files and the errors users can trigger.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include <fstream>

#include "core/error.hpp"
#include "raster/foldover.hpp"
#include "synth/baseline.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/foldover.hpp"
#include "synth/detail/footprint.hpp"
#include "synth/pattern_canvas.hpp"
#include "synth/placements_io.hpp"
#include "synth/render.hpp"
#include "synth/shapes.hpp"
#include "synth/synthesize.hpp"
#include "synth_fixtures.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

constexpr double kScale = 2.0;  // texels per metre
constexpr double kWidth = 10.0, kDelta = 3.0;

Synthesis run_sparse(const Exemplar& e, const Ribbon& r, const GridSpec& canvas,
                     const SparseRaster<std::uint8_t>* forbidden, SynthParams params = {}) {
  if (params.scale == 0.0) params.scale = kScale;
  auto backend = detail::make_cpu_backend();
  return detail::synthesize_on(*backend, e, r, canvas, forbidden, params);
}

// On a dense canvas: one tile covering it (these canvases are under 256 cells a side).
Synthesis run(const Exemplar& e, const Ribbon& r, const GridSpec& canvas,
              const Raster<std::uint8_t>* forbidden, SynthParams params = {}) {
  const SparseRaster<std::uint8_t> one_tile =
      forbidden ? sparse_from_dense(*forbidden, std::uint8_t(0), 0) : SparseRaster<std::uint8_t>();
  return run_sparse(e, r, canvas, forbidden ? &one_tile : nullptr, params);
}

// A disc of forbidden pixels on the top half of the ribbon at 40 % of its length.
Raster<std::uint8_t> forbidden_disc(const Ribbon& ribbon, const GridSpec& canvas) {
  const Piece& p = ribbon.pieces[ribbon.pieces.size() * 2 / 5];
  const Vec2 centre = lerp(p.top_left, p.bottom_left, 0.2);
  Raster<std::uint8_t> f(canvas.width, canvas.height, 0);
  for (int r = 0; r < canvas.height; ++r)
    for (int c = 0; c < canvas.width; ++c)
      if (distance(canvas.pixel_centre_world(c, r), centre) < 1.6) f.at(c, r) = 1;
  return f;
}

class Shapes : public ::testing::TestWithParam<const char*> {};

TEST_P(Shapes, NoOpaqueTexelOnForbiddenOrFoldedPixels) {
  const Exemplar chain = test::chain_exemplar(72, 28, 16);
  const Ribbon ribbon = make_ribbon(make_shape(GetParam(), 60.0), {kWidth, kDelta});
  const GridSpec canvas = test::canvas_around(ribbon, 0.5, 2.0);
  const Raster<std::uint8_t> disc = forbidden_disc(ribbon, canvas);
  SynthParams params;
  params.allow_empty_pieces = true;
  const Synthesis s = run(chain, ribbon, canvas, &disc, params);
  const RenderedPattern out = render_pattern(chain, ribbon, s, canvas, Window::whole(canvas));
  const SparseRaster<std::uint8_t> sparse_disc = sparse_from_dense(disc);
  const SparseRaster<std::uint8_t> avoid = detail::combined_avoidance(ribbon, canvas, &sparse_disc);
  EXPECT_EQ(count_avoidance_violations(out, avoid), 0);
  std::int64_t covered = 0, forbidden = 0, folded = 0;
  SparseRaster<std::uint8_t> folds(canvas.width, canvas.height, 0);
  add_tiles(folds, canvas_tiles(ribbon, canvas, folds.tile_size()));
  add_foldovers(ribbon, canvas, folds);
  for (int row = 0; row < canvas.height; ++row)
    for (int col = 0; col < canvas.width; ++col) {
      const float coverage = out.coverage.at(col, row);
      if (avoid.at(col, row)) {
        ++forbidden;
        ASSERT_EQ(coverage, 0.0f) << "pixel " << col << ", " << row;
      }
      folded += folds.at(col, row);
      covered += coverage > 0.5f;
    }
  EXPECT_GT(forbidden, 10);
  EXPECT_GT(covered, 200);  // a real pattern was drawn
  if (std::string(GetParam()) == "hairpin") {
    EXPECT_GT(folded, canvas.cell_count() / 1000);
    EXPECT_GE(forbidden, folded);
  }
}

// Synthesis reads the canvas only on the tiles within kCanvasHalo of a piece: 8-cell tiles there
// and nothing else give the dense canvas's result, even where the dense one forbids every cell
// off those tiles.
TEST_P(Shapes, SparseCanvasOnTheRibbonsTilesGivesTheDenseResult) {
  const Exemplar chain = test::chain_exemplar(72, 28, 16);
  const Ribbon ribbon = make_ribbon(make_shape(GetParam(), 60.0), {kWidth, kDelta});
  const GridSpec canvas = test::canvas_around(ribbon, 0.5, 2.0);
  const Raster<std::uint8_t> disc = forbidden_disc(ribbon, canvas);
  constexpr int kTile = 8;
  const std::vector<TileIndex> tiles = canvas_tiles(ribbon, canvas, kTile);
  SparseRaster<std::uint8_t> sparse(canvas.width, canvas.height, 0, kTile);
  add_tiles(sparse, tiles);
  Raster<std::uint8_t> dense = disc;
  for (int row = 0; row < canvas.height; ++row)
    for (int col = 0; col < canvas.width; ++col) {
      if (sparse.has_tile({col / kTile, row / kTile})) {
        sparse.set(col, row, disc.at(col, row));
      } else {
        dense.at(col, row) = 1;
      }
    }
  const int all_tiles = sparse.tiles_x() * sparse.tiles_y();
  // A straight ribbon fills its box; the curved ones leave tiles out.
  if (std::string(GetParam()) != "line") {
    EXPECT_LT(int(tiles.size()), all_tiles);
  }
  SynthParams params;
  params.allow_empty_pieces = true;
  const Synthesis a = run_sparse(chain, ribbon, canvas, &sparse, params);
  const Synthesis b = run(chain, ribbon, canvas, &dense, params);
  EXPECT_EQ(a.total_cost, b.total_cost);
  EXPECT_EQ(a.valid_counts, b.valid_counts);
  ASSERT_EQ(a.placements.size(), b.placements.size());
  int stitched = 0;
  for (std::size_t i = 0; i < a.placements.size(); ++i) {
    EXPECT_EQ(a.placements[i].ux, b.placements[i].ux) << i;
    EXPECT_EQ(a.placements[i].uy, b.placements[i].uy) << i;
    EXPECT_EQ(a.placements[i].empty, b.placements[i].empty) << i;
    EXPECT_EQ(a.placements[i].stitch, b.placements[i].stitch) << i;
    stitched += !a.placements[i].stitch.empty();
  }
  EXPECT_GT(stitched, 0);
  // The check reads the same tiles: no violation on the sparse canvas either.
  const RenderedPattern out = render_pattern(chain, ribbon, a, canvas, Window::whole(canvas));
  EXPECT_EQ(count_avoidance_violations(out, detail::combined_avoidance(ribbon, canvas, &sparse)),
            0);
}

INSTANTIATE_TEST_SUITE_P(Synth, Shapes,
                         ::testing::Values("line", "arc", "s-curve", "circle", "hairpin"));

TEST(Synthesize, SeamsBeatTheParametricBaselineAndStitchingLowersThem) {
  const Exemplar chain = test::chain_exemplar(90, 28, 17);
  for (const char* shape : {"arc", "s-curve", "heart"}) {
    const Ribbon ribbon = make_ribbon(make_shape(shape, 60.0), {kWidth, kDelta});
    const GridSpec canvas = test::canvas_around(ribbon, 0.5, 2.0);
    const Synthesis s = run(chain, ribbon, canvas, nullptr);
    const Synthesis base = parametric_baseline(chain, ribbon, kScale);
    std::printf("%s: synthesized %.1f, stitched %.1f, parametric %.1f (colour units per seam)\n",
                shape, s.mean_seam_cost, s.mean_seam_cost_stitched, base.mean_seam_cost);
    EXPECT_LT(s.mean_seam_cost, base.mean_seam_cost) << shape;
    EXPECT_GT(s.mean_seam_cost, 0.0) << shape;
    // Alignment never hurts; it helps where curvature tilts edges most (the heart's cusps).
    EXPECT_LE(s.mean_seam_cost_stitched, s.mean_seam_cost) << shape;
    if (std::string(shape) == "heart") {
      EXPECT_LT(s.mean_seam_cost_stitched, s.mean_seam_cost);
    }
    EXPECT_EQ(double(s.total_cost) /
                  (ribbon.closed ? ribbon.pieces.size() : ribbon.pieces.size() - 1) / 16.0,
              s.mean_seam_cost);
  }
}

TEST(Synthesize, MinCoverageKeepsTheOptimumOffNearlyEmptyPieces) {
  // The real ridge band (samples/exemplars) has two stray opaque texels above the band: with
  // the paper's rule ("not empty") a 48-texel piece holding only them is valid and seams for
  // free with transparent edges, so the optimum (Omega = 0) shows almost nothing.
  const Exemplar band =
      load_exemplar((test::source_dir() / "samples/exemplars/ridge_band_200x64.png").string());
  const Ribbon ribbon = make_ribbon(make_shape("s-curve", 400.0), {48.0, 40.0});
  const GridSpec canvas = test::canvas_around(ribbon, 1.0, 4.0);
  auto mean_coverage = [&](double min_coverage, Synthesis* out) {
    SynthParams params;
    params.scale = 1.0;
    params.min_coverage = min_coverage;
    params.objective = Objective::paper;
    *out = run(band, ribbon, canvas, nullptr, params);
    const RenderedPattern r = render_pattern(band, ribbon, *out, canvas, Window::whole(canvas));
    double sum = 0.0;
    std::int64_t inside = 0;
    for (int row = 0; row < canvas.height; ++row)
      for (int col = 0; col < canvas.width; ++col) {
        const Vec2 w = canvas.pixel_centre_world(col, row);
        bool in_piece = false;
        for (const Piece& p : ribbon.pieces)
          in_piece = in_piece || detail::piece_winding(p, w) != 0;
        if (!in_piece) continue;
        ++inside;
        sum += r.coverage.at(col, row);
      }
    return sum / double(inside);
  };
  Synthesis paper, covered;
  const double paper_coverage = mean_coverage(0.0, &paper);
  const double covered_coverage = mean_coverage(0.3, &covered);
  std::printf(
      "ridge band: min_coverage 0: Omega %lld, coverage %.3f, valid/piece %d; "
      "0.3: Omega %lld, coverage %.3f, valid/piece %d\n",
      (long long)paper.total_cost, paper_coverage, paper.valid_counts[1],
      (long long)covered.total_cost, covered_coverage, covered.valid_counts[1]);
  EXPECT_EQ(paper.total_cost, 0);
  EXPECT_LT(paper_coverage, 0.01);
  EXPECT_GT(covered.total_cost, 0);
  EXPECT_GE(covered_coverage, 0.3 * 0.9);  // rendering resamples: a little below the texel rule
  for (std::size_t i = 0; i < covered.valid_counts.size(); ++i)
    EXPECT_LT(covered.valid_counts[i], paper.valid_counts[i]) << "piece " << i;

  SynthParams bad;
  bad.scale = 1.0;
  bad.min_coverage = 1.0;
  try {
    run(band, ribbon, canvas, nullptr, bad);
    FAIL() << "min_coverage 1 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("min_coverage must be in [0, 1)"), std::string::npos)
        << e.what();
  }
}

TEST(Synthesize, FeatheringMeetsChannelsAcrossSeamsAndKeepsTheCoverage) {
  // The ridge band's pieces come from different parts of the exemplar: colours and heights
  // step at the seams. Feathering blends the channels across each seam, never the coverage.
  const Exemplar band = load_exemplar(
      (test::source_dir() / "samples/exemplars/ridge_band_200x64.png").string(),
      {.height_path =
           (test::source_dir() / "samples/exemplars/ridge_band_200x64_height.tif").string()});
  const Ribbon ribbon = make_ribbon(make_shape("s-curve", 400.0), {48.0, 40.0});
  const GridSpec canvas = test::canvas_around(ribbon, 0.5, 4.0);
  SynthParams params;
  params.scale = 1.0;
  params.min_coverage = 0.3;
  const Synthesis s = run(band, ribbon, canvas, nullptr, params);
  const Window whole = Window::whole(canvas);
  const RenderedPattern sharp = render_pattern(band, ribbon, s, canvas, whole, true, 0.0);
  const RenderedPattern soft = render_pattern(band, ribbon, s, canvas, whole, true, 6.0);
  EXPECT_EQ(sharp.coverage.pixels, soft.coverage.pixels);
  const int height = band.channel_index("height");
  ASSERT_GE(height, 0);
  // Mean |step| of the height channel between the pixels 0.5 m either side of every seam.
  auto seam_step = [&](const RenderedPattern& r) {
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i + 1 < ribbon.pieces.size(); ++i) {
      const Piece& p = ribbon.pieces[i];
      const Vec2 along = normalized(p.top_right - p.top_left);
      for (double t = 0.02; t < 1.0; t += 0.02) {
        const Vec2 on = lerp(p.top_right, p.bottom_right, t);
        const Vec2 a = canvas.world_to_pixel(on - along * 0.5);
        const Vec2 b = canvas.world_to_pixel(on + along * 0.5);
        const int ac = int(a.x), ar = int(a.y), bc = int(b.x), br = int(b.y);
        if (r.coverage.at(ac, ar) < 0.9f || r.coverage.at(bc, br) < 0.9f) continue;
        sum += std::abs(r.channels[std::size_t(height)].at(bc, br) -
                        r.channels[std::size_t(height)].at(ac, ar));
        ++count;
      }
    }
    EXPECT_GT(count, 50);
    return sum / count;
  };
  const double sharp_step = seam_step(sharp), soft_step = seam_step(soft);
  std::printf("height step across seams: %.2f m sharp, %.2f m feathered over 6 m\n", sharp_step,
              soft_step);
  EXPECT_LT(soft_step, 0.5 * sharp_step);
  // Away from every seam the pieces are exact copies either way.
  for (std::size_t i = 0; i < ribbon.pieces.size(); ++i) {
    const Piece& p = ribbon.pieces[i];
    const Vec2 centre = canvas.world_to_pixel(
        lerp(lerp(p.top_left, p.bottom_right, 0.5), lerp(p.top_right, p.bottom_left, 0.5), 0.5));
    const int c = int(centre.x), r = int(centre.y);
    EXPECT_EQ(sharp.channels[std::size_t(height)].at(c, r),
              soft.channels[std::size_t(height)].at(c, r))
        << "piece " << i;
  }
}

TEST(Synthesize, SameSeedSameBytesOnAnyThreadCount) {
  const Exemplar chain = test::chain_exemplar(72, 28, 16);
  const Ribbon ribbon = make_ribbon(make_shape("s-curve", 60.0), {kWidth, kDelta});
  const GridSpec canvas = test::canvas_around(ribbon, 0.5, 2.0);
  SynthParams params;
  params.seed = 7;
  const Synthesis a = run(chain, ribbon, canvas, nullptr, params);
  Synthesis b;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    b = run(chain, ribbon, canvas, nullptr, params);
  }
  ASSERT_EQ(a.placements.size(), b.placements.size());
  for (std::size_t i = 0; i < a.placements.size(); ++i) {
    EXPECT_EQ(a.placements[i].ux, b.placements[i].ux);
    EXPECT_EQ(a.placements[i].uy, b.placements[i].uy);
    EXPECT_EQ(a.placements[i].stitch, b.placements[i].stitch);
  }
  EXPECT_EQ(a.total_cost, b.total_cost);
  params.seed = 8;
  const Synthesis c = run(chain, ribbon, canvas, nullptr, params);
  const Synthesis optimum = run(chain, ribbon, canvas, nullptr);
  EXPECT_LE(optimum.total_cost, std::min(a.total_cost, c.total_cost));
  bool differs = false;
  for (std::size_t i = 0; i < a.placements.size(); ++i)
    differs |= a.placements[i].ux != c.placements[i].ux || a.placements[i].uy != c.placements[i].uy;
  EXPECT_TRUE(differs);
}

TEST(Synthesize, ClosedExactModeIsNeverWorseThanTheApproximation) {
  const Exemplar chain = test::chain_exemplar(72, 28, 16);
  const Ribbon ribbon = make_ribbon(make_shape("circle", 24.0), {kWidth, 4.0});
  const GridSpec canvas = test::canvas_around(ribbon, 0.5, 2.0);
  SynthParams params;
  const Synthesis approx = run(chain, ribbon, canvas, nullptr, params);
  params.closed_mode = ClosedMode::exact;
  const Synthesis exact = run(chain, ribbon, canvas, nullptr, params);
  std::printf("circle: exact cycle %lld, approximate cycle %lld\n", (long long)exact.total_cost,
              (long long)approx.total_cost);
  EXPECT_LE(exact.total_cost, approx.total_cost);
  EXPECT_TRUE(exact.closed);
}

TEST(Synthesize, PlacementsRoundTripThroughJson) {
  const Exemplar chain = test::chain_exemplar(72, 28, 16);
  const Ribbon ribbon = make_ribbon(make_shape("arc", 40.0), {kWidth, kDelta});
  const GridSpec canvas = test::canvas_around(ribbon, 0.5, 2.0);
  const Synthesis s = run(chain, ribbon, canvas, nullptr);
  test::TempDir dir;
  const std::string path = (dir / "placements.json").string();
  save_placements(s, "chain.png", path);
  std::string exemplar;
  const Synthesis back = load_placements(path, &exemplar);
  EXPECT_EQ(exemplar, "chain.png");
  EXPECT_EQ(back.total_cost, s.total_cost);
  const auto r1 = render_pattern(chain, ribbon, s, canvas, Window::whole(canvas));
  const auto r2 = render_pattern(chain, ribbon, back, canvas, Window::whole(canvas));
  EXPECT_EQ(r1.coverage.pixels, r2.coverage.pixels);
  std::ofstream(dir / "bad.json") << R"({"format": "terraweave.placements", "version": 1})";
  try {
    load_placements((dir / "bad.json").string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("exemplar"), std::string::npos);
  }
  // A position beyond int (found by fuzz/placements_loader; UBSan: float-cast-overflow) is
  // refused by name, never cast.
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(path));
  doc["placements"][0]["uy"] = -3.92e20;
  std::ofstream(dir / "huge.json") << doc.dump();
  try {
    load_placements((dir / "huge.json").string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("placements[0].uy"), std::string::npos) << e.what();
  }
}

TEST(Synthesize, BadInputsNameTheCulprit) {
  const Exemplar chain = test::chain_exemplar(72, 28, 16);
  const Curve line = make_shape("line", 30.0);
  EXPECT_THROW(make_ribbon(line, {0.0, 3.0}), Error);
  EXPECT_THROW(make_ribbon(line, {10.0, -1.0}), Error);
  EXPECT_THROW(make_ribbon(line, {10.0, 31.0}), Error);
  EXPECT_THROW(make_shape("spiral", 10.0), Error);
  const Ribbon ribbon = make_ribbon(line, {kWidth, kDelta});
  const GridSpec canvas = test::canvas_around(ribbon, 0.5, 2.0);
  SynthParams params;
  params.scale = -1.0;
  EXPECT_THROW(run(chain, ribbon, canvas, nullptr, params), Error);
  Raster<std::uint8_t> all(canvas.width, canvas.height, 1);
  params.scale = kScale;
  params.feature_label = "feature 42";
  try {
    run(chain, ribbon, canvas, &all, params);
    FAIL();
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("piece 0 of feature 42 at ("), std::string::npos) << m;
    EXPECT_NE(m.find("no valid position in exemplar chain(test)"), std::string::npos) << m;
    EXPECT_NE(m.find("avoidance"), std::string::npos) << m;
  }
  // A ribbon narrower than a solid band: no position clears top and bottom edges.
  const Exemplar band = test::band_exemplar(30, 24, 2, 20, 1);
  try {
    run(band, make_ribbon(line, {3.0, kDelta}), canvas, nullptr, params);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("top and bottom edges"), std::string::npos) << e.what();
  }
  params.allow_empty_pieces = true;
  const Synthesis empty = run(chain, ribbon, canvas, &all, params);
  for (const Placement& p : empty.placements) EXPECT_TRUE(p.empty);
}

}  // namespace
}  // namespace tw
