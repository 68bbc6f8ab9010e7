// Footprints in vector space and the crossing check (issue #21): a line buffered by its half
// width keeps off others exactly, even where it is far narrower than the growth mesh.
#include "ornament/footprints.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "ornament/crossings.hpp"
#include "ornament/grow.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

TEST(Footprints, LinesOverlapWhenCloserThanTheirHalfWidths) {
  FootprintIndex index;
  EXPECT_EQ(index.add_line({{0, 0}, {100, 0}}, 1.0), 0);  // a 2 m lane along y = 0
  EXPECT_EQ(index.add_polygon({{{50, 50}, {60, 50}, {60, 60}, {50, 60}}}), 1);
  EXPECT_EQ(index.size(), 2);
  // 1.49 m from the lane's centre line: a 1 m-wide line (half 0.5) overlaps, a line does not.
  EXPECT_TRUE(index.overlaps({{10, 1.49}, {20, 1.49}}, 0.5));
  EXPECT_FALSE(index.overlaps({{10, 1.51}, {20, 1.51}}, 0.5));
  EXPECT_FALSE(index.overlaps({{10, 1.49}, {20, 1.49}}, 0.0));
  // Only a segment's middle comes near: the exact distance, not the vertices'.
  EXPECT_TRUE(index.overlaps({{40, 30}, {45, 0.5}, {50, 30}}, 0.0));
  EXPECT_TRUE(index.overlaps({{-5, -5}, {5, 5}}, 0.0));  // across it
  // Areas: inside one, or within the half width of its edge.
  EXPECT_EQ(index.overlapped({{54, 54}, {56, 56}}, 0.0), std::vector<int>{1});
  EXPECT_EQ(index.overlapped({{61.5, 40}, {61.5, 70}}, 2.0), std::vector<int>{1});
  EXPECT_TRUE(index.overlapped({{62.5, 40}, {62.5, 70}}, 2.0).empty());
  EXPECT_EQ(index.overlapped({{55, -10}, {55, 70}}, 0.0), (std::vector<int>{0, 1}));
}

TEST(Footprints, LinesMayMeetEndToEndButNotCross) {
  FootprintIndex index;
  index.add_line({{0, 0}, {10, 0}, {20, 5}}, 0.0);
  EXPECT_TRUE(index.crossed({{20, 5}, {30, 5}}).empty());                    // from its end
  EXPECT_TRUE(index.crossed({{0, 0}, {-5, 5}, {-10, 0}}).empty());           // from its start
  EXPECT_EQ(index.crossed({{5, -5}, {5, 5}}), std::vector<int>{0});          // across
  EXPECT_EQ(index.crossed({{10, 0}, {10, 5}}), std::vector<int>{0});         // from its middle (T)
  EXPECT_EQ(index.crossed({{20, 5}, {10, 0}}), std::vector<int>{0});         // back along it
  EXPECT_EQ(index.crossed({{-5, 0}, {0, 0}, {3, 0}}), std::vector<int>{0});  // runs on past
}

struct World {
  GridSpec grid;
  Raster<float> heights;
  Raster<std::uint8_t> allowed;
};

// A rolling hillside at 10 m (a 320 m square); allowed: a disc of 150 m. A 2 m lane at
// x = 1163 runs north-south between two columns of vertices (x = 1155, 1165), so no vertex
// lies on it and the mesh's mask cannot see it.
World coarse_hillside() {
  World w;
  const int n = 32;
  w.grid = {n, n, 1000.0, 2000.0, 10.0, 10.0};
  w.heights = Raster<float>(n, n);
  w.allowed = Raster<std::uint8_t>(n, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const Vec2 p = w.grid.pixel_centre_world(c, r);
      w.heights.at(c, r) = float(0.1 * (p.y - 1840.0) + 4.0 * std::sin((p.x - 1000.0) / 37.0) *
                                                            std::cos((p.y - 2000.0) / 41.0));
      w.allowed.at(c, r) = distance(p, {1160.0, 1840.0}) < 150.0;
    }
  return w;
}

const std::vector<Vec2> kLane = {{1163.0, 1650.0}, {1163.0, 2050.0}};

ElementSet sample(const char* name) {
  return read_element_set(test::source_dir() / "samples/ornaments" / (std::string(name) + ".json"));
}

TEST(Footprints, GrowthKeepsOffAFootprintNarrowerThanTheMesh) {
  const World w = coarse_hillside();
  const TerrainSurface surface(w.heights, w.grid, Window::whole(w.grid));
  FootprintIndex lane;
  lane.add_line(kLane, 1.0);
  GrowthParams params;
  params.seed = 3;
  const ElementSet hedge = sample("hedge"), ditch = sample("ditch");
  // Without the exact test the hedges (2 m: half width 1) grow across the lane.
  const GrowthResult blind = grow_ornaments(surface, w.allowed, hedge, params);
  const CrossingCheck before = check_crossings({{&blind.lines, 1.0, nullptr}}, lane);
  EXPECT_GT(before.total.feature, 0);
  EXPECT_EQ(before.total.grown, 0);  // in a class, lines never crossed
  ASSERT_FALSE(before.first.empty());
  EXPECT_EQ(describe(before.first.front(), {"hedges"}, {"the lane"}).find("hedges FID "), 0u);

  const KeepOff keep_off{&lane, 1.0, nullptr};
  const GrowthResult hedges = grow_ornaments(surface, w.allowed, hedge, params, keep_off);
  EXPECT_GT(hedges.rejected_footprint, 0);
  EXPECT_GT(hedges.elements, 10);
  // Ditches (1 m: half width 0.5) after them, off the lane and the hedges' footprints.
  FootprintIndex before_ditches;
  before_ditches.add_line(kLane, 1.0);
  for (const GrownLine& l : hedges.lines) before_ditches.add_line(l.points, 1.0);
  const GrowthResult ditches =
      grow_ornaments(surface, w.allowed, ditch, params, KeepOff{&before_ditches, 0.5, nullptr});
  EXPECT_GT(ditches.elements, 3);
  EXPECT_GT(ditches.rejected_footprint, 0);
  const CrossingCheck after =
      check_crossings({{&hedges.lines, 1.0, nullptr}, {&ditches.lines, 0.5, nullptr}}, lane);
  EXPECT_EQ(after.total.total(), 0);
  // Ditches grown blind to the hedges overlap them: counted in the ditches' set.
  const GrowthResult blind_ditches =
      grow_ornaments(surface, w.allowed, ditch, params, KeepOff{&lane, 0.5, nullptr});
  const CrossingCheck overlapping =
      check_crossings({{&hedges.lines, 1.0, nullptr}, {&blind_ditches.lines, 0.5, nullptr}}, lane);
  EXPECT_EQ(overlapping.per_set[0].total(), 0);
  EXPECT_GT(overlapping.per_set[1].grown, 0);
  EXPECT_EQ(overlapping.per_set[1].feature, 0);
}

TEST(Footprints, ForbiddenCellsOfAFinerGridAreKeptOff) {
  const World w = coarse_hillside();
  const TerrainSurface surface(w.heights, w.grid, Window::whole(w.grid));
  // A 1 m grid over the same ground with a 3 m-wide strip of nodata cells at x 1161..1164.
  ForbiddenCells cells;
  cells.grid = {320, 320, 1000.0, 2000.0, 1.0, 1.0};
  cells.window = Window::whole(cells.grid);
  cells.allowed = Raster<std::uint8_t>(320, 320);
  for (int r = 0; r < 320; ++r)
    for (int c = 0; c < 320; ++c) cells.allowed.at(c, r) = c < 161 || c >= 164;
  GrowthParams params;
  params.seed = 3;
  const ElementSet hedge = sample("hedge");
  const FootprintIndex none;
  const GrowthResult blind = grow_ornaments(surface, w.allowed, hedge, params);
  EXPECT_GT(check_crossings({{&blind.lines, 1.0, &cells}}, none).total.forbidden, 0);
  const GrowthResult kept =
      grow_ornaments(surface, w.allowed, hedge, params, KeepOff{nullptr, 1.0, &cells});
  EXPECT_EQ(check_crossings({{&kept.lines, 1.0, &cells}}, none).total.total(), 0);
  EXPECT_GT(kept.elements, 10);
}

}  // namespace
}  // namespace tw
