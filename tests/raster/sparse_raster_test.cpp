// Sparse tiled rasters: tiles only where asked, the dense results on them (avoidance, fold-overs,
// copies between canvases on one lattice).
#include "raster/sparse_raster.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "raster/avoidance.hpp"
#include "raster/foldover.hpp"
#include "raster/junction_discs.hpp"

namespace tw {
namespace {

// 0.5 m cells, 300 x 200, over [1000, 1150] x [2020, 2120].
const GridSpec kGrid{300, 200, 1000.0, 2120.0, 0.5, 0.5};

// A meander that runs south-west to north-east and turns back on itself in a hairpin narrower
// than its ribbon (fold-overs).
Curve meander_with_hairpin() {
  Curve c;
  for (int k = 0; k <= 20; ++k) c.points.push_back({1010.0 + 3.0 * k, 2030.0 + 2.0 * k});
  for (int k = 1; k < 18; ++k) {  // a clockwise half-turn of radius 1.5 m around (1070, 2068.5)
    const double a = std::numbers::pi / 2 - std::numbers::pi * k / 18;
    c.points.push_back({1070.0 + 1.5 * std::cos(a), 2068.5 + 1.5 * std::sin(a)});
  }
  for (int k = 0; k <= 10; ++k) c.points.push_back({1070.0 - 3.0 * k, 2067.0});
  return c;
}

TEST(SparseRaster, AbsentTilesAndOutsideReadTheBackground) {
  SparseRaster<std::uint8_t> r(300, 200, 7, 64);
  EXPECT_EQ(r.tiles_x(), 5);
  EXPECT_EQ(r.tiles_y(), 4);
  EXPECT_EQ(r.at(10, 10), 7);
  EXPECT_EQ(r.at(-1, 0), 7);
  EXPECT_EQ(r.at(300, 0), 7);
  r.set(290, 199, 3);  // the bottom-right tile, clipped to 44 x 8 cells
  EXPECT_EQ(r.tile_count(), 1u);
  EXPECT_EQ(r.at(290, 199), 3);
  EXPECT_EQ(r.at(289, 199), 7);  // same tile, background fill
  EXPECT_EQ(r.at(10, 10), 7);
  EXPECT_EQ(r.tile_window({4, 3}), (Window{256, 192, 44, 8}));
  ASSERT_NE(r.tile({4, 3}), nullptr);
  EXPECT_EQ(r.tile({4, 3})->width, 44);
  EXPECT_EQ(r.tile({0, 0}), nullptr);
  EXPECT_EQ(r.allocated_bytes(), 20 * sizeof(std::int32_t) + 44 * 8);
  // 0 is the dense canvas: one tile for the whole raster.
  const SparseRaster<std::uint8_t> dense(300, 200, 0, 0);
  EXPECT_EQ(dense.tiles_x() * dense.tiles_y(), 1);
}

TEST(SparseRaster, RibbonTilesCoverEveryPieceAndItsHaloAndNoMore) {
  const Ribbon ribbon = make_ribbon(meander_with_hairpin(), {4.0, 1.5});
  const int tile = 16;
  const std::vector<TileIndex> tiles = ribbon_tiles(ribbon, kGrid, tile, 2);
  SparseRaster<std::uint8_t> listed(kGrid.width, kGrid.height, 0, tile);
  add_tiles(listed, tiles);
  // Every cell within 2 of a piece's box lies on a listed tile; every listed tile meets one.
  SparseRaster<std::uint8_t> needed(kGrid.width, kGrid.height, 0, tile);
  for (const Piece& p : ribbon.pieces) {
    double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
    for (const Vec2 w : {p.top_left, p.bottom_left, p.bottom_right, p.top_right}) {
      const Vec2 q = kGrid.world_to_pixel(w);
      x0 = std::min(x0, q.x), x1 = std::max(x1, q.x), y0 = std::min(y0, q.y),
      y1 = std::max(y1, q.y);
    }
    for (int row = int(std::floor(y0)) - 2; row <= int(std::floor(y1)) + 2; ++row)
      for (int col = int(std::floor(x0)) - 2; col <= int(std::floor(x1)) + 2; ++col)
        if (kGrid.width > col && col >= 0 && kGrid.height > row && row >= 0) {
          ASSERT_TRUE(listed.has_tile({col / tile, row / tile})) << col << ", " << row;
          needed.set(col, row, 1);
        }
  }
  EXPECT_EQ(needed.tile_count(), tiles.size());
  // A diagonal ribbon: a small share of the grid's 19 x 13 tiles.
  EXPECT_LT(tiles.size(), 19u * 13u / 3u);
  for (std::size_t i = 1; i < tiles.size(); ++i)  // row-major, no repeats
    EXPECT_LT(std::pair(tiles[i - 1].ty, tiles[i - 1].tx), std::pair(tiles[i].ty, tiles[i].tx));
}

TEST(SparseRaster, AvoidanceAndFoldoversOnTilesEqualTheDenseMap) {
  const Ribbon earlier = make_ribbon(Curve{{{1005, 2025}, {1140, 2060}}, false}, {5.0, 2.0});
  const Ribbon current = make_ribbon(meander_with_hairpin(), {4.0, 1.5});
  AvoidanceInputs in;
  in.polygons = {{{{1020, 2060}, {1045, 2062}, {1040, 2040}, {1018, 2045}}}};
  in.lines = {{{1050, 2110}, {1080, 2050}}};
  in.line_widths = {3.0};
  in.ribbons = {&earlier};
  in.junction_discs = junction_discs({Junction{{1040, 2050}, {}, false}}, {3.0});
  // Dense: the whole grid, then the current ribbon's fold-overs.
  const Window whole = Window::whole(kGrid);
  Raster<std::uint8_t> dense = build_avoidance_map(in, kGrid, whole).forbidden;
  const Raster<std::uint8_t> folds = foldover_mask(current, kGrid, whole);
  std::size_t fold_count = 0;
  for (std::size_t i = 0; i < dense.pixels.size(); ++i) {
    dense.pixels[i] |= folds.pixels[i];
    fold_count += folds.pixels[i];
  }
  ASSERT_GT(fold_count, 20u);
  // Sparse: 16-cell tiles along the current ribbon only.
  SparseRaster<std::uint8_t> sparse(kGrid.width, kGrid.height, 0, 16);
  add_tiles(sparse, ribbon_tiles(current, kGrid, 16, 2));
  burn_avoidance(in, kGrid, sparse);
  add_foldovers(current, kGrid, sparse);
  std::size_t compared = 0, forbidden = 0;
  for (int row = 0; row < kGrid.height; ++row)
    for (int col = 0; col < kGrid.width; ++col) {
      if (!sparse.has_tile({col / 16, row / 16})) {
        ASSERT_EQ(sparse.at(col, row), 0);
        continue;
      }
      ASSERT_EQ(sparse.at(col, row), dense.at(col, row)) << col << ", " << row;
      ++compared;
      forbidden += dense.at(col, row);
    }
  EXPECT_GT(forbidden, fold_count);  // polygons, lines, discs and the earlier ribbon too
  EXPECT_LT(compared, std::size_t(kGrid.cell_count()) / 2);
}

TEST(SparseRaster, CopiesBetweenCanvasesOnOneLattice) {
  // The target's origin lies 37 cells east and 21 cells north of the source's.
  const GridSpec source_grid{120, 90, 1000.0, 2100.0, 0.5, 0.5};
  const GridSpec target_grid{100, 100, 1018.5, 2110.5, 0.5, 0.5};
  SparseRaster<std::uint8_t> source(120, 90, 0, 32);
  for (int k = 0; k < 90; ++k) source.set(k + 20, k, 1);  // a diagonal
  SparseRaster<std::uint8_t> target(100, 100, 0, 32);
  for (const TileIndex t : {TileIndex{0, 0}, TileIndex{0, 1}, TileIndex{1, 2}, TileIndex{2, 3}})
    target.add_tile(t);  // half of the tiles the diagonal crosses, and one it misses
  add_on_lattice(source, source_grid, target, target_grid);
  int set = 0;
  for (int row = 0; row < 100; ++row)
    for (int col = 0; col < 100; ++col) {
      // Source cell (col + 37, row - 21) in the target's frame.
      const bool on_source = source.at(col + 37, row - 21) != 0;
      const bool kept = target.has_tile({col / 32, row / 32});
      ASSERT_EQ(target.at(col, row), on_source && kept ? 1 : 0) << col << ", " << row;
      set += target.at(col, row);
    }
  EXPECT_GT(set, 40);
}

TEST(SparseRaster, FromDenseKeepsOnlyTilesThatDiffer) {
  Raster<std::uint8_t> dense(100, 70, 0);
  dense.at(5, 5) = 1;
  dense.at(99, 69) = 2;
  const SparseRaster<std::uint8_t> sparse = sparse_from_dense(dense, std::uint8_t(0), 32);
  EXPECT_EQ(sparse.tile_count(), 2u);
  for (int row = 0; row < 70; ++row)
    for (int col = 0; col < 100; ++col) ASSERT_EQ(sparse.at(col, row), dense.at(col, row));
}

}  // namespace
}  // namespace tw
