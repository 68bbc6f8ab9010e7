#include "terrain/height_ops.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "geo/resample.hpp"
#include "terrain/detail/profiles.hpp"
#include "terrain_test_support.hpp"

namespace tw {
namespace {

// Row of the pixel centres at world y = size - row - 0.5; a feature along world y = Y runs
// between rows size - Y - 1 and size - Y.
constexpr int kSize = 200;

TEST(ShapeTerrain, RiverBedIsDepthBelowTheSurfaceAndBanksMeetTheTerrain) {
  const GridSpec grid = test::unit_grid(kSize);
  auto plane = [](double x, double) { return 100.0 - 0.05 * x; };  // falls eastwards
  const Raster<float> before = test::heights_from(grid, plane);
  Raster<float> h = before;
  auto river = test::feature(FeatureKind::river, 7, {{20.0, 100.5}, {180.0, 100.5}}, 6.0);
  river.river = {2.5, 4.0, 10.0, 0.0, {}};
  shape_terrain(h, grid, Window::whole(grid), {river}, {});
  const int centre_row = kSize - 101;  // centres at y = 100.5
  // A spring, not a pit: the depth eases in over width + bank + falloff = 20 m.
  EXPECT_GT(h.at(21, centre_row), before.at(21, centre_row) - 0.5);
  for (int col = 41; col < 175; ++col) {
    for (int dr = -3; dr <= 3; ++dr)  // |across| <= 3 = half the width
      EXPECT_NEAR(h.at(col, centre_row + dr), before.at(col, centre_row + dr) - 2.5, 2e-3)
          << col << " " << dr;
    // Bank top: beyond bank + falloff the terrain is untouched.
    EXPECT_EQ(h.at(col, centre_row + 18), before.at(col, centre_row + 18));
    EXPECT_EQ(h.at(col, centre_row - 18), before.at(col, centre_row - 18));
    // The bank rises monotonically from the bed to the terrain.
    for (int dr = 3; dr < 17; ++dr) {
      EXPECT_LE(h.at(col, centre_row + dr) - before.at(col, centre_row + dr),
                h.at(col, centre_row + dr + 1) - before.at(col, centre_row + dr + 1) + 1e-5);
    }
  }
}

TEST(ShapeTerrain, WaterSurfaceNeverRisesDownstreamOverABump) {
  const GridSpec grid = test::unit_grid(kSize);
  auto bumpy = [](double x, double y) {
    return 100.0 - 0.05 * x + 6.0 * std::exp(-std::pow((x - 100.0) / 12.0, 2)) + 0.01 * y;
  };
  const Raster<float> before = test::heights_from(grid, bumpy);
  Raster<float> h = before;
  auto river = test::feature(FeatureKind::river, 3, {{15.0, 100.5}, {185.0, 100.5}}, 4.0);
  river.river.depth = 2.0;
  river.river.min_slope = 0.001;
  river.river.max_carve = 1e9;  // the surface alone: max_carve's default would meet the bump
  shape_terrain(h, grid, Window::whole(grid), {river}, {});
  const int centre_row = kSize - 101;
  float upstream_min = before.at(16, centre_row);
  for (int col = 16; col < 184; ++col) {
    upstream_min = std::min(upstream_min, before.at(col, centre_row));
    if (col > 15 + 30) {
      EXPECT_LE(h.at(col, centre_row), upstream_min - 2.0 + 1e-3) << col;
    }
    EXPECT_LE(h.at(col + 1, centre_row), h.at(col, centre_row) - 0.001 + 1e-4) << col;
  }
  // Through the bump the bed is far below the terrain (a gorge), never a dam.
  EXPECT_LT(h.at(100, centre_row), before.at(100, centre_row) - 6.0);
}

TEST(ShapeTerrain, RoadIsLevelAcrossWithinGradeAlongAndMeetsTheTerrain) {
  const GridSpec grid = test::unit_grid(kSize);
  auto hills = [](double x, double y) { return 50.0 + 12.0 * std::sin(x / 9.0) + 0.3 * y; };
  const Raster<float> before = test::heights_from(grid, hills);
  Raster<float> h = before;
  auto road = test::feature(FeatureKind::road, 11, {{10.0, 100.0}, {190.0, 100.0}}, 6.0);
  road.road = {0.08, 2.0, 10.0, 30.0, {}, {}};
  shape_terrain(h, grid, Window::whole(grid), {road}, {});
  const int north = kSize - 101, south = kSize - 100;  // rows either side of y = 100
  for (int col = 10; col < 190; ++col) {
    // Level over the road and its shoulders: |across| <= 3 + 2 metres.
    for (int dr = -4; dr <= 4; ++dr)
      EXPECT_NEAR(h.at(col, north + dr), h.at(col, north), 0.01) << col << " " << dr;
    // Within the grade along the road, sampled on the raster.
    if (col + 1 < 190) {
      EXPECT_LE(std::abs(h.at(col + 1, north) - h.at(col, north)), 0.08 + 1e-4) << col;
    }
    // Untouched beyond the falloff, and continuous with the terrain at its edge.
    const int outer_n = north - 15, outer_s = south + 15;  // 15.5 m > 3 + 2 + 10
    EXPECT_EQ(h.at(col, outer_n), before.at(col, outer_n));
    EXPECT_EQ(h.at(col, outer_s), before.at(col, outer_s));
    // 14.5 m out, 0.5 m inside the falloff edge: the smoothstep leaves < 1 % of the cut.
    const float cut = std::abs(h.at(col, north) - before.at(col, north - 14));
    EXPECT_LE(std::abs(h.at(col, north - 14) - before.at(col, north - 14)), 0.01f * cut + 1e-3);
  }
  // The terrain had grades up to 12/9 = 1.3: the road really was graded.
  float steepest = 0;
  for (int col = 10; col < 189; ++col)
    steepest = std::max(steepest, std::abs(before.at(col + 1, north) - before.at(col, north)));
  EXPECT_GT(steepest, 1.0f);
}

TEST(ShapeTerrain, ARingRoadIsGradedAllAroundWithoutAStepWhereItCloses) {
  // A closed road on a tilted plane: its profile is periodic, so the grade holds across the
  // closing point too (an open profile would jump there by the tilt over the ring).
  const GridSpec grid = test::unit_grid(kSize);
  auto tilted = [](double x, double y) { return 50.0 + 0.25 * x + 3.0 * std::sin(y / 7.0); };
  const Raster<float> before = test::heights_from(grid, tilted);
  Raster<float> h = before;
  const Vec2 centre{100.0, 100.0};
  const double radius = 60.0;
  std::vector<Vec2> ring;
  for (int k = 0; k < 180; ++k) {
    const double a = 2.0 * std::acos(-1.0) * k / 180.0;
    ring.push_back(centre + Vec2{radius * std::cos(a), radius * std::sin(a)});
  }
  auto road = test::feature(FeatureKind::road, 5, ring, 6.0);
  road.centerline.closed = true;
  road.road = {0.06, 2.0, 10.0, 40.0, {}, {}};
  shape_terrain(h, grid, Window::whole(grid), {road}, {});
  // Sample the surface on the centreline every 2 degrees (about 2.1 m), through the start.
  auto at = [&](double degrees) {
    const double a = degrees * std::acos(-1.0) / 180.0;
    const Vec2 p = grid.world_to_pixel(centre + Vec2{radius * std::cos(a), radius * std::sin(a)});
    return sample_height_bilinear(h, grid, grid.pixel_to_world(p));
  };
  const double step = radius * 2.0 * std::acos(-1.0) / 180.0;
  double steepest = 0.0;
  for (int d = -90; d < 270; d += 2) {
    const double rise = std::abs(at(d + 2) - at(d));
    steepest = std::max(steepest, rise / step);
    EXPECT_LE(rise, 0.06 * step + 0.03) << "between " << d << " and " << d + 2 << " degrees";
  }
  std::printf("ring road: steepest centreline grade %.4f (max_grade 0.06)\n", steepest);
  // Graded, not flattened: the ring still climbs eastwards.
  EXPECT_GT(at(0) - at(180), 5.0) << at(0) << " " << at(180);
}

TEST(Profiles, ClosedProfilesArePeriodicAndWithinGradeAcrossTheClosingPoint) {
  // A loop of 101 samples (100 per period) climbing 30 m then dropping back at one point, the
  // worst case for an open profile.
  std::vector<double> v(101);
  for (std::size_t i = 0; i < 100; ++i) v[i] = 0.3 * double(i);
  v[100] = v[0];
  const double step = 1.0, grade = 0.5;
  const auto graded = detail::limit_grade_closed(v, step, grade);
  EXPECT_DOUBLE_EQ(graded.front(), graded.back());
  for (std::size_t i = 0; i + 1 < graded.size(); ++i)
    EXPECT_LE(std::abs(graded[i + 1] - graded[i]), grade * step + 1e-12) << i;
  // Where v is already within grade of all its loop neighbours it is kept: the middle of the
  // climb moves by less than where the drop was.
  EXPECT_LT(std::abs(graded[50] - v[50]), std::abs(graded[99] - v[99]));
  // Open grading of the same samples keeps a step of metres between its last and first
  // sample, which are the same point of the loop.
  const auto open = detail::limit_grade(v, step, grade);
  EXPECT_GT(std::abs(open.back() - open.front()), 10.0);

  // Moving average: wraps (the average at 0 mixes the end of the loop), constant stays.
  const auto smooth = detail::moving_average_closed(v, step, 10.0);  // 11 samples
  EXPECT_DOUBLE_EQ(smooth.front(), smooth.back());
  double expected = 0.0;
  for (int k = -5; k <= 5; ++k) expected += v[std::size_t((k + 100) % 100)];
  EXPECT_NEAR(smooth[0], expected / 11.0, 1e-9);
  EXPECT_NEAR(smooth[50], v[50], 1e-9);  // linear part: the centred mean is the value
  const auto flat = detail::moving_average_closed(std::vector<double>(101, 4.5), step, 400.0);
  for (double x : flat) EXPECT_DOUBLE_EQ(x, 4.5);
}

TEST(ShapeTerrain, CrossingRoadsMeetAtOneLevelWithinGrade) {
  // Terrain waving along x only: the east-west road is graded nearly flat, the north-south road
  // follows the terrain, so at the crossing their own levels differ by metres.
  const GridSpec grid = test::unit_grid(kSize);
  auto waves = [](double x, double) { return 50.0 + 10.0 * std::sin(x / 9.0); };
  const Raster<float> before = test::heights_from(grid, waves);
  Raster<float> h = before;
  auto east_west = test::feature(FeatureKind::road, 1, {{10.0, 100.5}, {190.0, 100.5}}, 6.0);
  auto north_south = test::feature(FeatureKind::road, 2, {{100.5, 10.0}, {100.5, 190.0}}, 6.0);
  for (auto* road : {&east_west, &north_south}) road->road = {0.05, 1.0, 10.0, 30.0, {}, {}};
  shape_terrain(h, grid, Window::whole(grid), {east_west, north_south}, {});
  const int centre = kSize - 101;  // the row and column whose centres lie on the two roads
  double steepest_ew = 0.0, steepest_ns = 0.0;
  for (int k = 15; k < 185; ++k) {
    steepest_ew = std::max(steepest_ew, double(std::abs(h.at(k + 1, centre) - h.at(k, centre))));
    steepest_ns = std::max(steepest_ns, double(std::abs(h.at(100, k + 1) - h.at(100, k))));
  }
  std::printf("crossing: steepest grade east-west %.4f, north-south %.4f (max_grade 0.05)\n",
              steepest_ew, steepest_ns);
  EXPECT_LE(steepest_ew, 0.05 + 1e-3);
  EXPECT_LE(steepest_ns, 0.05 + 1e-3);
  double spread = 0.0;
  for (int dr = -2; dr <= 2; ++dr)
    for (int dc = -2; dc <= 2; ++dc)
      spread = std::max(spread, double(std::abs(h.at(100 + dc, centre + dr) - h.at(100, centre))));
  std::printf("crossing square spread %.4f\n", spread);
  // One level over the crossing square (3 m either way of the centre).
  for (int dr = -2; dr <= 2; ++dr)
    for (int dc = -2; dc <= 2; ++dc)
      EXPECT_NEAR(h.at(100 + dc, centre + dr), h.at(100, centre), 0.05 * 4.0) << dr << " " << dc;
  // And the north-south road still follows the terrain away from the crossing.
  EXPECT_GT(std::abs(h.at(100, 20) - h.at(100, centre)), 0.5);

  // A diagonal road (45 degrees): its platform reaches further along each road.
  Raster<float> d = before;
  auto diagonal = test::feature(FeatureKind::road, 3, {{20.5, 20.5}, {180.5, 180.5}}, 6.0);
  diagonal.road = north_south.road;
  shape_terrain(d, grid, Window::whole(grid), {east_west, diagonal}, {});
  double steepest_diagonal = 0.0;
  steepest_ew = 0.0;
  for (int k = 15; k < 185; ++k)
    steepest_ew = std::max(steepest_ew, double(std::abs(d.at(k + 1, centre) - d.at(k, centre))));
  for (double t = 30.0; t < 170.0; t += 1.0) {
    const double a = sample_height_bilinear(d, grid, {t, t});
    const double b = sample_height_bilinear(d, grid, {t + 1.0, t + 1.0});
    steepest_diagonal = std::max(steepest_diagonal, std::abs(b - a) / std::sqrt(2.0));
  }
  std::printf("diagonal crossing: steepest grade east-west %.4f, diagonal %.4f\n", steepest_ew,
              steepest_diagonal);
  EXPECT_LE(steepest_ew, 0.05 + 1e-3);
  EXPECT_LE(steepest_diagonal, 0.05 + 5e-3);  // bilinear reads between pixel centres
}

TEST(ShapeTerrain, FeaturesLeftOutOverNodataPullNothingDown) {
  // The west half is nodata. A river and a road lying there are left out; the river that
  // starts at the first one's mouth and the road that ends on the second one stay at the level
  // of their own terrain (a left-out feature has no profile: reading it as 0 m would drag them
  // down by the whole terrain height).
  const GridSpec grid = test::unit_grid(kSize);
  Raster<float> h = test::heights_from(grid, [](double x, double) { return 300.0 - 0.01 * x; });
  for (int row = 0; row < kSize; ++row)
    for (int col = 0; col < 80; ++col) h.at(col, row) = std::numeric_limits<float>::quiet_NaN();
  const Raster<float> before = h;
  auto feeder = test::feature(FeatureKind::river, 1, {{10.0, 60.5}, {70.0, 60.5}}, 4.0);
  auto river = test::feature(FeatureKind::river, 2, {{70.0, 60.5}, {190.0, 60.5}}, 4.0);
  river.river.depth = 2.0;
  auto through = test::feature(FeatureKind::road, 3, {{20.0, 140.0}, {20.0, 180.0}}, 6.0);
  auto spur = test::feature(FeatureKind::road, 4, {{20.0, 160.0}, {190.0, 160.0}}, 6.0);
  shape_terrain(h, grid, Window::whole(grid), {feeder, river, through, spur}, {});
  const int river_row = kSize - 61, road_row = kSize - 161;
  for (int col = 100; col < 185; ++col) {
    EXPECT_NEAR(h.at(col, river_row), before.at(col, river_row) - 2.0, 0.05) << col;
    EXPECT_NEAR(h.at(col, road_row), before.at(col, road_row), 0.5) << col;
  }
}

TEST(ShapeTerrain, RidgeRaisesTheCrestByItsHeight) {
  const GridSpec grid = test::unit_grid(kSize);
  Raster<float> h(kSize, kSize, 10.0f);
  auto ridge = test::feature(FeatureKind::ridge, 2, {{100.5, 20.0}, {100.5, 180.0}}, 4.0);
  ridge.ridge = {8.0, 30.0, 1.5};
  shape_terrain(h, grid, Window::whole(grid), {ridge}, {});
  const int crest = 100;  // centres at x = 100.5
  EXPECT_FLOAT_EQ(h.at(crest, 100), 18.0f);
  EXPECT_FLOAT_EQ(h.at(crest + 1, 100), 18.0f);  // within the crest width
  // Centred on the crest's edge: the cell's mean weight is just below 1 (docs/terrain.md).
  EXPECT_NEAR(h.at(crest + 2, 100), 18.0f, 0.01f);
  for (int dc = 2; dc < 32; ++dc) EXPECT_LE(h.at(crest + dc + 1, 100), h.at(crest + dc, 100));
  EXPECT_GT(h.at(crest + 15, 100), 10.0f);
  EXPECT_EQ(h.at(crest + 33, 100), 10.0f);
}

TEST(ShapeTerrain, NodataIsNeverWrittenNorReadAsAHeight) {
  const GridSpec grid = test::unit_grid(kSize);
  Raster<float> h(kSize, kSize, 20.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int row = 80; row < 120; ++row)
    for (int col = 90; col < 110; ++col) h.at(col, row) = nan;
  auto road = test::feature(FeatureKind::road, 1, {{20.0, 100.0}, {180.0, 100.0}}, 8.0);
  auto river = test::feature(FeatureKind::river, 2, {{100.0, 20.0}, {100.0, 180.0}}, 6.0);
  shape_terrain(h, grid, Window::whole(grid), {road, river}, {});
  for (int row = 0; row < kSize; ++row)
    for (int col = 0; col < kSize; ++col) {
      const bool hole = row >= 80 && row < 120 && col >= 90 && col < 110;
      if (hole) {
        EXPECT_TRUE(std::isnan(h.at(col, row)));
      } else if (std::abs(col + 0.5 - 100.0) > 3.0 + 6.0 + 20.0) {
        // Away from the river, only the road acts: a flat profile at 20, never pulled
        // towards a nodata value.
        EXPECT_NEAR(h.at(col, row), 20.0f, 1e-4) << col << " " << row;
      }
    }
}

TEST(ShapeTerrain, LaterKindsOverwriteWhereTheyHoldFully) {
  const GridSpec grid = test::unit_grid(kSize);
  const Raster<float> before =
      test::heights_from(grid, [](double x, double) { return 30.0 + 0.02 * x; });
  Raster<float> h = before;
  auto road = test::feature(FeatureKind::road, 1, {{100.5, 20.0}, {100.5, 180.0}}, 6.0);
  auto river = test::feature(FeatureKind::river, 2, {{20.0, 100.5}, {180.0, 100.5}}, 6.0);
  shape_terrain(h, grid, Window::whole(grid), {road, river}, {});  // road after river by default
  // At the crossing the road surface (the terrain there, 32.01) wins over the river bed.
  EXPECT_NEAR(h.at(100, 99), before.at(100, 99), 1e-3);
  EXPECT_LT(h.at(60, 99), before.at(60, 99) - 2.0);  // the river elsewhere
  TerrainParams river_last;
  river_last.precedence = {FeatureKind::ridge, FeatureKind::road, FeatureKind::river};
  Raster<float> h2 = before;
  shape_terrain(h2, grid, Window::whole(grid), {road, river}, river_last);
  EXPECT_LT(h2.at(100, 99), before.at(100, 99) - 2.0);
}

TEST(ShapeTerrain, RoadsSharingAnEndpointMeetLevelWithoutASpike) {
  const GridSpec grid = test::unit_grid(kSize);
  auto slope = [](double x, double y) { return 40.0 + 0.2 * x + 8.0 * std::sin(y / 11.0); };
  const Raster<float> before = test::heights_from(grid, slope);
  Raster<float> h = before;
  const Vec2 junction{100.0, 100.0};
  auto east = test::feature(FeatureKind::road, 1, {{20.0, 100.0}, junction}, 6.0);
  auto north = test::feature(FeatureKind::road, 2, {junction, {100.0, 190.0}}, 6.0);
  shape_terrain(h, grid, Window::whole(grid), {east, north}, {});
  // No spike, no trench: near the junction every height lies within the range of the
  // terrain around it (the road profiles are smoothed terrain).
  const Vec2 jp = grid.world_to_pixel(junction);
  float lo = 1e9f, hi = -1e9f;
  for (int row = int(jp.y) - 40; row < int(jp.y) + 40; ++row)
    for (int col = int(jp.x) - 40; col < int(jp.x) + 40; ++col) {
      lo = std::min(lo, before.at(col, row));
      hi = std::max(hi, before.at(col, row));
    }
  for (int row = int(jp.y) - 20; row < int(jp.y) + 20; ++row)
    for (int col = int(jp.x) - 20; col < int(jp.x) + 20; ++col) {
      EXPECT_GE(h.at(col, row), lo - 0.01f);
      EXPECT_LE(h.at(col, row), hi + 0.01f);
    }
  // On both road surfaces near the junction, neighbours differ by at most the grade: the
  // surfaces meet level instead of with a step.
  for (int row = int(jp.y) - 10; row < int(jp.y) + 3; ++row)
    for (int col = int(jp.x) - 10; col < int(jp.x) + 3; ++col) {
      const Vec2 p = grid.pixel_centre_world(col, row);
      const bool on_east = std::abs(p.y - 100.0) < 2.5 && p.x < 102.0;
      const bool on_north = std::abs(p.x - 100.0) < 2.5 && p.y > 98.0;
      if (!on_east && !on_north) continue;
      EXPECT_LE(std::abs(h.at(col + 1, row) - h.at(col, row)), 0.08f * 1.5f + 0.01f)
          << col << " " << row;
      EXPECT_LE(std::abs(h.at(col, row + 1) - h.at(col, row)), 0.08f * 1.5f + 0.01f)
          << col << " " << row;
    }
  // The plan pins both profiles to one height at the shared end (they differ unpinned).
  const TerrainPlan plan = plan_terrain(before, grid, {east, north}, {});
  EXPECT_EQ(plan.profiles[0].back(), plan.profiles[1].front());
  // Both roads end at the same height: the two centre pixels beside the junction agree.
  EXPECT_NEAR(h.at(int(jp.x) - 1, int(jp.y)), h.at(int(jp.x), int(jp.y) - 1), 0.2);
}

TEST(ShapeTerrain, ATJunctionRoadMeetsTheThroughRoadAtItsLevel) {
  const GridSpec grid = test::unit_grid(kSize);
  auto hills = [](double x, double y) { return 70.0 + 0.15 * y + 6.0 * std::sin(x / 17.0); };
  const Raster<float> before = test::heights_from(grid, hills);
  Raster<float> h = before;
  auto through = test::feature(FeatureKind::road, 1, {{10.0, 100.0}, {190.0, 100.0}}, 6.0);
  auto branch = test::feature(FeatureKind::road, 2, {{80.0, 190.0}, {100.0, 100.0}}, 6.0);
  Raster<float> alone = before;
  shape_terrain(alone, grid, Window::whole(grid), {through}, {});
  shape_terrain(h, grid, Window::whole(grid), {through, branch}, {});
  // The through road keeps its own level at the junction; the branch arrives at it.
  const int jc = 100, jr = kSize - 101;
  // (Within the grade over the half pixel between the pixel centre and the junction point.)
  EXPECT_NEAR(h.at(jc, jr), alone.at(jc, jr), 0.08 * std::sqrt(0.5));
  // Walking up the branch from the junction, the road rises within the grade: no step.
  for (int row = jr - 1; row > jr - 40; --row) {
    const double x = 100.0 - 20.0 * (kSize - row - 0.5 - 100.0) / 90.0;
    const int col = int(std::floor(x));
    const int prev_col = int(std::floor(100.0 - 20.0 * (kSize - row - 1.5 - 100.0) / 90.0));
    const double ds = std::hypot(1.0, col - prev_col);
    EXPECT_LE(std::abs(h.at(col, row) - h.at(prev_col, row + 1)), 0.08 * ds + 0.05) << row;
  }
}

TEST(ShapeTerrain, ATributaryIsEasedDownToTheMainRiverSurface) {
  const GridSpec grid = test::unit_grid(kSize);
  // The main river runs east along a valley floor; the tributary comes down a side slope and
  // would end well above the main surface if nothing joined them.
  // A hollow upstream on the valley floor keeps the main river's surface below the floor
  // downstream of it (the running minimum), so the tributary arrives too high.
  auto valley = [](double x, double y) {
    return 50.0 - 0.02 * x + 0.3 * std::abs(y - 60.0) -
           3.0 * std::exp(-std::pow((x - 40.0) / 8.0, 2));
  };
  const Raster<float> before = test::heights_from(grid, valley);
  Raster<float> h = before;
  auto main = test::feature(FeatureKind::river, 1, {{5.0, 60.5}, {195.0, 60.5}}, 8.0);
  auto trib = test::feature(FeatureKind::river, 2, {{100.5, 190.0}, {100.5, 60.5}}, 4.0);
  main.river.depth = 2.0;
  trib.river.depth = 1.0;
  // The surfaces alone: the tributary's descent to the main surface is deeper than
  // max_carve's default, which would let it meet the terrain instead (CarveLimit tests).
  main.river.max_carve = trib.river.max_carve = 1e9;
  shape_terrain(h, grid, Window::whole(grid), {main, trib}, {});
  // Along the tributary the bed never rises downstream, right into the confluence.
  const int col = 100;
  for (int row = kSize - 189; row < kSize - 62; ++row)
    EXPECT_LE(h.at(col, row + 1), h.at(col, row) + 1e-4) << row;
  // The water surfaces (bed + depth) meet at the mouth: no waterfall in the plan, although
  // the tributary's own terrain ends 1.8 m above the main surface there.
  const TerrainPlan plan = plan_terrain(before, grid, {main, trib}, {});
  const double main_surface = detail::profile_at(plan.profiles[0], plan.steps[0], 95.5) + 2.0;
  EXPECT_NEAR(plan.profiles[1].back() + 1.0, main_surface, 0.01);
  // Held down by the hollow upstream (its floor at x = 40, 0.5 m off the valley axis).
  EXPECT_NEAR(main_surface, 50.0 - 0.8 - 3.0 + 0.15, 0.05);
}

TEST(ShapeTerrain, TilesAndThreadCountsGiveIdenticalBits) {
  const GridSpec grid = test::unit_grid(kSize);
  const Raster<float> before = test::heights_from(grid, [](double x, double y) {
    return 60.0 + 5.0 * std::sin(x / 13.0) * std::cos(y / 17.0);
  });
  std::vector<TerrainFeature> features = {
      test::feature(FeatureKind::road, 1, {{5.0, 20.0}, {80.0, 120.0}, {195.0, 140.0}}, 7.0),
      test::feature(FeatureKind::river, 2, {{10.0, 190.0}, {120.0, 90.0}, {190.0, 5.0}}, 9.0),
      test::feature(FeatureKind::ridge, 3, {{30.0, 30.0}, {170.0, 60.0}}, 3.0),
      test::feature(FeatureKind::road, 4, {{80.0, 120.0}, {60.0, 195.0}}, 5.0)};
  Raster<float> whole = before;
  shape_terrain(whole, grid, Window::whole(grid), features, {});
  const TerrainPlan plan = plan_terrain(before, grid, features, {});
  Raster<float> tiled = before;
  for (const Window w : {Window{0, 0, 77, 200}, Window{77, 0, 123, 91}, Window{77, 91, 123, 109}})
    apply_terrain(tiled, grid, w, plan);
  Raster<float> serial = before;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    shape_terrain(serial, grid, Window::whole(grid), features, {});
  }
  EXPECT_EQ(0, std::memcmp(whole.pixels.data(), tiled.pixels.data(), whole.pixels.size() * 4));
  EXPECT_EQ(0, std::memcmp(whole.pixels.data(), serial.pixels.data(), whole.pixels.size() * 4));
  EXPECT_NE(0, std::memcmp(whole.pixels.data(), before.pixels.data(), whole.pixels.size() * 4));
}

TEST(ShapeTerrain, ShapesAHeightfieldInPlace) {
  Heightfield hf;
  hf.grid = test::unit_grid(60);
  hf.height = Raster<float>(60, 60, 5.0f);
  auto ridge = test::feature(FeatureKind::ridge, 9, {{30.5, 5.0}, {30.5, 55.0}}, 2.0);
  ridge.ridge.height = 3.0;
  ridge.ridge.falloff = 10.0;
  shape_heightfield(hf, {ridge});
  EXPECT_FLOAT_EQ(hf.height.at(30, 30), 8.0f);
  EXPECT_FLOAT_EQ(hf.height.at(2, 30), 5.0f);
}

TEST(ShapeTerrain, BadFeaturesNameTheirFid) {
  const GridSpec grid = test::unit_grid(20);
  Raster<float> h(20, 20, 0.0f);
  auto f = test::feature(FeatureKind::road, 42, {{1.0, 1.0}, {1.0, 1.0}}, 4.0);
  try {
    shape_terrain(h, grid, Window::whole(grid), {f}, {});
    FAIL() << "expected tw::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("FID 42"), std::string::npos) << e.what();
  }
  f.centerline.points = {{1.0, 1.0}, {5.0, 5.0}};
  f.width = -1.0;
  EXPECT_THROW(shape_terrain(h, grid, Window::whole(grid), {f}, {}), Error);
}

}  // namespace
}  // namespace tw
