#include "terrain/conform.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ribbon/curve.hpp"
#include "terrain/height_ops.hpp"
#include "terrain/splat.hpp"
#include "terrain_test_support.hpp"

namespace tw {
namespace {

// 200 x 200 cells of 10 m (2 km square, world (0, 0) .. (2000, 2000)).
GridSpec ten_metre_grid() {
  return GridSpec{200, 200, 0.0, 2000.0, 10.0, 10.0};
}

// A valley (40 m deep, floor along x = 805) falling gently to the south.
double valley(double x, double y) {
  return 100.0 + 0.01 * y - 40.0 * std::exp(-std::pow((x - 805.0) / 150.0, 2.0));
}

// The river drawn 200 m east of the valley floor, running south.
const Curve kOffsetRiver{{{1005.0, 1950.0}, {1005.0, 50.0}}, false};

TEST(Conform, ARiverOffsetFromItsValleyMovesOntoTheFloor) {
  const GridSpec grid = ten_metre_grid();
  const Raster<float> h = test::heights_from(grid, valley);
  const ConformResult r = conform_line(h, grid, kOffsetRiver, {400.0});
  ASSERT_TRUE(r.conformed) << r.kept_because;
  // The ends stay; in between the line runs on the valley floor.
  EXPECT_EQ(r.line.points.front(), kOffsetRiver.points.front());
  EXPECT_EQ(r.line.points.back(), kOffsetRiver.points.back());
  EXPECT_NEAR(r.max_move, 200.0, 10.0);
  int on_floor = 0, middle = 0;
  for (const Vec2 p : r.line.points) {
    if (p.y < 600.0 || p.y > 1400.0) continue;
    ++middle;
    on_floor += std::abs(p.x - 805.0) <= 10.0;
  }
  EXPECT_GT(middle, 30);
  EXPECT_EQ(on_floor, middle);
  EXPECT_GT(r.mean_move, 120.0);
  EXPECT_LE(r.mean_move, r.max_move);
  // The line keeps running downstream: y never increases along it by more than the half
  // cell between an exact end and the centre of its cell.
  for (std::size_t i = 1; i < r.line.points.size(); ++i)
    EXPECT_LE(r.line.points[i].y, r.line.points[i - 1].y + 5.0);
}

TEST(Conform, ACorridorNarrowerThanTheOffsetCannotReachTheFloor) {
  const GridSpec grid = ten_metre_grid();
  const Raster<float> h = test::heights_from(grid, valley);
  const ConformResult r = conform_line(h, grid, kOffsetRiver, {100.0});
  ASSERT_TRUE(r.conformed);
  EXPECT_LE(r.max_move, 100.0 + 1e-9);
  EXPECT_GT(r.max_move, 80.0);  // as far towards the valley as the corridor allows
}

TEST(Conform, WithoutACorridorOrOnAFlatDemTheLineStays) {
  const GridSpec grid = ten_metre_grid();
  const Raster<float> valley_h = test::heights_from(grid, valley);
  const ConformResult none = conform_line(valley_h, grid, kOffsetRiver, {0.0});
  EXPECT_FALSE(none.conformed);
  EXPECT_EQ(none.line.points, kOffsetRiver.points);
  EXPECT_EQ(none.max_move, 0.0);

  const Raster<float> flat(grid.width, grid.height, 50.0f);
  const ConformResult r = conform_line(flat, grid, kOffsetRiver, {400.0});
  ASSERT_TRUE(r.conformed);
  EXPECT_LT(r.max_move, 1e-6);  // on cell centres already: nothing to gain by moving
}

TEST(Conform, ARidgeLineSnapsToTheCrest) {
  const GridSpec grid = ten_metre_grid();
  const Raster<float> h =
      test::heights_from(grid, [](double x, double y) { return 200.0 - valley(x, y); });
  const ConformResult r = conform_line(h, grid, kOffsetRiver, {400.0, ConformTarget::crest});
  ASSERT_TRUE(r.conformed);
  EXPECT_NEAR(r.max_move, 200.0, 10.0);
  for (const Vec2 p : r.line.points) {
    if (p.y > 600.0 && p.y < 1400.0) {
      EXPECT_NEAR(p.x, 805.0, 10.0);
    }
  }
}

// Metres of `line` over nodata cells of `h` (sampled every 0.5 m), and its length.
std::pair<double, double> length_over_nodata(const Raster<float>& h, const GridSpec& grid,
                                             const Curve& line) {
  const auto cumulative = cumulative_lengths(line);
  const double total = cumulative.back(), step = 0.5;
  double over = 0.0;
  for (double s = 0.5 * step; s < total; s += step) {
    const Vec2 px = grid.world_to_pixel(point_at(line, cumulative, s));
    const int col = int(std::floor(px.x)), row = int(std::floor(px.y));
    if (col >= 0 && row >= 0 && col < grid.width && row < grid.height && std::isnan(h.at(col, row)))
      over += step;
  }
  return {over, total};
}

TEST(Conform, NodataCostsMoreThanAnyPathOverValidCells) {
  const GridSpec grid = ten_metre_grid();
  Raster<float> h = test::heights_from(grid, valley);
  // The valley floor is nodata between y = 800 and 1200 (a lake cut out of the DEM): nothing
  // can be carved there, so the line goes round it on valid cells (beside it on the slope)
  // rather than through it, where the river would vanish.
  for (int row = 0; row < grid.height; ++row)
    for (int col = 0; col < grid.width; ++col) {
      const Vec2 p = grid.pixel_centre_world(col, row);
      if (std::abs(p.x - 805.0) < 60.0 && p.y > 800.0 && p.y < 1200.0)
        h.at(col, row) = std::numeric_limits<float>::quiet_NaN();
    }
  const ConformResult r = conform_line(h, grid, kOffsetRiver, {400.0});
  ASSERT_TRUE(r.conformed);
  const auto [over, total] = length_over_nodata(h, grid, r.line);
  EXPECT_GT(total, 1900.0);
  EXPECT_EQ(over, 0.0);  // not a metre over nodata: a valid path exists
  int beside = 0;
  for (const Vec2 p : r.line.points) {
    if (p.y < 850.0 || p.y > 1150.0) continue;
    ++beside;
    EXPECT_GE(std::abs(p.x - 805.0), 60.0) << p.y;
    EXPECT_LE(std::abs(p.x - 805.0), 80.0) << p.y;  // as close to the floor as valid cells go
  }
  EXPECT_GT(beside, 20);
  // Away from the lake it is still on the floor (the smoothing is kept).
  for (const Vec2 p : r.line.points) {
    if (p.y > 300.0 && p.y < 600.0) {
      EXPECT_LE(std::abs(p.x - 805.0), 10.0) << p.y;
    }
  }
  // The drawn line crosses no nodata; one drawn through the lake crosses 400 m of it and its
  // conformed line none.
  const Curve through{{{805.0, 1950.0}, {805.0, 50.0}}, false};
  EXPECT_NEAR(length_over_nodata(h, grid, through).first, 400.0, 10.0);
  const ConformResult around = conform_line(h, grid, through, {400.0});
  ASSERT_TRUE(around.conformed);
  EXPECT_EQ(length_over_nodata(h, grid, around.line).first, 0.0);

  // A corridor wholly over nodata keeps the line.
  const Raster<float> none(grid.width, grid.height, std::numeric_limits<float>::quiet_NaN());
  const ConformResult kept = conform_line(none, grid, kOffsetRiver, {400.0});
  EXPECT_FALSE(kept.conformed);
  EXPECT_EQ(kept.line.points, kOffsetRiver.points);
}

TEST(Conform, NodataAcrossTheWholeCorridorIsCrossedTheShortestWay) {
  const GridSpec grid = ten_metre_grid();
  Raster<float> h = test::heights_from(grid, valley);
  // A band of nodata across the whole grid, y 1000..1100, drawn across at a slant: the
  // path cannot go round, so it crosses it straight (100 m), never along it.
  for (int row = 0; row < grid.height; ++row)
    for (int col = 0; col < grid.width; ++col) {
      const Vec2 p = grid.pixel_centre_world(col, row);
      if (p.y > 1000.0 && p.y < 1100.0) h.at(col, row) = std::numeric_limits<float>::quiet_NaN();
    }
  const ConformResult r = conform_line(h, grid, kOffsetRiver, {400.0});
  ASSERT_TRUE(r.conformed);
  EXPECT_NEAR(length_over_nodata(h, grid, r.line).first, 100.0, 15.0);
}

TEST(Conform, ATributaryEndingOnTheTrunkStillMeetsItAfterBothMove) {
  const GridSpec grid = ten_metre_grid();
  const Raster<float> h = test::heights_from(grid, valley);
  const Curve tributary{{{1600.0, 1000.0}, {1300.0, 1005.0}, {1005.0, 1000.0}}, false};
  const std::vector<Curve> drawn = {kOffsetRiver, tributary};
  std::vector<Curve> conformed;
  for (const Curve& c : drawn) conformed.push_back(conform_line(h, grid, c, {400.0}).line);
  ASSERT_GT(distance_to_line(conformed[0], tributary.points.back()), 150.0);  // left behind
  const Curve trunk = conformed[0];
  reattach_ends(drawn, conformed, {10.0, 10.0});
  EXPECT_LT(distance_to_line(conformed[0], conformed[1].points.back()), 1e-9);
  EXPECT_NEAR(conformed[1].points.back().x, 805.0, 10.0);  // on the valley floor
  EXPECT_EQ(conformed[1].points.front(), tributary.points.front());
  EXPECT_EQ(conformed[0].points, trunk.points);  // the trunk's ends touch no interior
}

// A spur 60 m high across the river's line (at y = 1000) on a plain falling to the south.
double spur(double, double y) {
  return 50.0 + 0.005 * y + 60.0 * std::exp(-std::pow((y - 1000.0) / 150.0, 2.0));
}

TerrainFeature spur_river(std::optional<double> max_carve) {
  auto river = test::feature(FeatureKind::river, 7, kOffsetRiver.points, 10.0);
  river.river.depth = 2.5;
  river.river.max_carve = max_carve;
  return river;
}

// What the never-rising bed would cut at the spur's top: its height above the lowest point
// of the plain upstream of it, plus the depth.
double unbounded_cut_at_the_spur() {
  double floor = spur(0.0, 1950.0);
  for (double y = 1950.0; y >= 1000.0; y -= 0.5) floor = std::min(floor, spur(0.0, y));
  return spur(0.0, 1000.0) - floor + 2.5;
}

double deepest_lowering(const Raster<float>& before, const Raster<float>& after) {
  double deepest = 0.0;
  for (std::size_t i = 0; i < before.pixels.size(); ++i)
    deepest = std::max(deepest, double(before.pixels[i]) - after.pixels[i]);
  return deepest;
}

TEST(CarveLimit, TheBedIsNeverMoreThanMaxCarveBelowTheTerrain) {
  const GridSpec grid = ten_metre_grid();
  const Raster<float> before = test::heights_from(grid, spur);
  Raster<float> h = before;
  const TerrainPlan plan = plan_terrain(h, grid, {spur_river(12.0)}, {});
  apply_terrain(h, grid, Window::whole(grid), plan);
  EXPECT_LE(deepest_lowering(before, h), 12.0 + 1e-3);
  const FeatureEarthwork& e = plan.earthwork.at(0);
  EXPECT_NEAR(e.max_cut, 12.0, 1e-9);
  // Where it was held: across the spur, worst at its top, by what the never-rising bed
  // needed beyond 12 m.
  EXPECT_GT(e.cut_limited.length, 200.0);
  EXPECT_NEAR(e.cut_limited.at.y, 1000.0, 20.0);
  EXPECT_NEAR(e.cut_limited.at.x, 1005.0, 1e-9);
  EXPECT_NEAR(e.cut_limited.excess, unbounded_cut_at_the_spur() - 12.0, 0.2);
  EXPECT_NEAR(e.cut_limited.along, 950.0, 20.0);
}

TEST(CarveLimit, TheDefaultIsTwoDepthsAndAnUnboundedRiverCutsTheSpur) {
  const GridSpec grid = ten_metre_grid();
  const Raster<float> before = test::heights_from(grid, spur);
  Raster<float> bounded = before, unbounded = before;
  shape_terrain(bounded, grid, Window::whole(grid), {spur_river(std::nullopt)}, {});
  EXPECT_EQ(kDefaultCarveDepths, 2.0);  // issue #21 item 6 (docs/terrain.md)
  EXPECT_LE(deepest_lowering(before, bounded), 2.0 * 2.5 + 1e-3);
  EXPECT_GT(deepest_lowering(before, bounded), 2.0 * 2.5 - 0.1);
  shape_terrain(unbounded, grid, Window::whole(grid), {spur_river(1e9)}, {});
  EXPECT_NEAR(deepest_lowering(before, unbounded), unbounded_cut_at_the_spur(), 0.2);  // as before
}

TEST(CarveLimit, RoadCutAndFillAreBounded) {
  const GridSpec grid = ten_metre_grid();
  const Raster<float> before = test::heights_from(grid, spur);
  auto road = test::feature(FeatureKind::road, 9, kOffsetRiver.points, 8.0);
  road.road.max_grade = 0.02;  // the spur (60 m over ~300 m) needs deep cutting
  road.road.max_cut = 6.0;
  road.road.max_fill = 4.0;
  Raster<float> h = before;
  const TerrainPlan plan = plan_terrain(h, grid, {road}, {});
  apply_terrain(h, grid, Window::whole(grid), plan);
  double cut = 0.0, fill = 0.0;
  for (std::size_t i = 0; i < h.pixels.size(); ++i) {
    cut = std::max(cut, double(before.pixels[i]) - h.pixels[i]);
    fill = std::max(fill, double(h.pixels[i]) - before.pixels[i]);
  }
  EXPECT_LE(cut, 6.0 + 1e-3);
  EXPECT_LE(fill, 4.0 + 1e-3);
  const FeatureEarthwork& e = plan.earthwork.at(0);
  EXPECT_NEAR(e.max_cut, 6.0, 1e-9);
  EXPECT_NEAR(e.max_fill, 4.0, 1e-9);
  EXPECT_GT(e.cut_limited.length, 0.0);
  EXPECT_GT(e.fill_limited.length, 0.0);
  EXPECT_NEAR(e.cut_limited.at.y, 1000.0, 40.0);  // the deepest cut is through the spur's top
}

// A 30 m river on a 1 km grid: each cell is lowered by the share of it the river covers.
TEST(CoarseGrid, ARiverNarrowerThanACellLowersItByItsShare) {
  const double cell = 1000.0, depth = 2.5, width = 30.0;
  const GridSpec grid{20, 20, 0.0, 20000.0, cell, cell};
  const Raster<float> before(grid.width, grid.height, 100.0f);
  auto river = test::feature(FeatureKind::river, 3, {{10500.0, 19500.0}, {10500.0, 500.0}}, width);
  river.river = {depth, 6.0, 20.0, 0.0, {}};
  Raster<float> h = before;
  shape_terrain(h, grid, Window::whole(grid), {river}, {});
  const double banks = 2.0 * (river.river.bank_width + river.river.falloff);
  const double deepest = deepest_lowering(before, h);
  EXPECT_LE(deepest, depth * (width + banks) / cell + 1e-4);  // 0.205 m, not 2.5 m
  EXPECT_GE(deepest, depth * width / cell);                   // but the river is there
  // Cells beside the river's column are untouched.
  for (int row = 2; row < 18; ++row) {
    EXPECT_EQ(h.at(9, row), 100.0f);
    EXPECT_EQ(h.at(11, row), 100.0f);
  }
  // Splat: the riverbed covers 30 m of the 1000 m cell, the banks 12 m.
  const SplatLayers s = compute_splat(grid, Window::whole(grid), {river}, {});
  EXPECT_NEAR(s.weights[3].at(10, 10), width / cell, 1e-6);  // riverbed
  EXPECT_NEAR(s.weights[4].at(10, 10), 12.0 / cell, 1e-6);   // bank
  EXPECT_NEAR(s.weights[0].at(10, 10), 1.0 - 42.0 / cell, 1e-6);
}

TEST(CoarseGrid, SplatIsNeverPaintedOnNodata) {
  const GridSpec grid = test::unit_grid(64);
  Raster<float> h(64, 64, 10.0f);
  for (int row = 0; row < 64; ++row)
    for (int col = 30; col < 64; ++col) h.at(col, row) = std::numeric_limits<float>::quiet_NaN();
  auto road = test::feature(FeatureKind::road, 4, {{5.0, 32.0}, {60.0, 32.0}}, 6.0);
  const SplatLayers s = compute_splat(grid, Window::whole(grid), {road}, {}, h);
  const int row = 31;  // y = 32.5, on the road
  EXPECT_GT(s.weights[1].at(20, row), 0.99f);
  for (int col = 30; col < 64; ++col) {
    EXPECT_EQ(s.weights[0].at(col, row), 1.0f);
    for (std::size_t m = 1; m < s.weights.size(); ++m) EXPECT_EQ(s.weights[m].at(col, row), 0.0f);
  }
  shape_terrain(h, grid, Window::whole(grid), {road}, {});
  for (int col = 30; col < 64; ++col) EXPECT_TRUE(std::isnan(h.at(col, row)));
}

}  // namespace
}  // namespace tw
