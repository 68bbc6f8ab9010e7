// Pixel windows of ribbons and points, and the window index over them.
#include "raster/footprint.hpp"
#include "raster/window_index.hpp"

#include <gtest/gtest.h>

namespace tw {
namespace {

// A piece reaching 5e11 m either side (a width of 1e12) overflowed int in ribbon_window,
// which then gave an empty window and the run "succeeded" with nothing forbidden.
TEST(RibbonWindow, APieceFarBeyondTheGridClampsToTheWholeGrid) {
  const GridSpec grid{100, 80, 500000.0, 5000000.0, 10.0, 10.0};
  Ribbon ribbon;
  ribbon.pieces.push_back(
      Piece{{500500.0, 5e11}, {500500.0, -5e11}, {500504.0, -5e11}, {500504.0, 5e11}, 0.0, 4.0});
  EXPECT_EQ(ribbon_window(ribbon, grid), (Window{49, 0, 3, 80}));
  ribbon.pieces[0] = Piece{{-5e11, -5e11}, {-5e11, 5e11}, {5e11, 5e11}, {5e11, -5e11}, 0.0, 4.0};
  EXPECT_EQ(ribbon_window(ribbon, grid), Window::whole(grid));
}

// A ribbon wholly beside the grid met it in a one-pixel strip along the near edge (the box
// started from the grid's extent, not from the pieces), so it touched the edge tiles.
TEST(RibbonWindow, ARibbonBesideTheGridHasAnEmptyWindow) {
  const GridSpec grid{100, 80, 0.0, 800.0, 10.0, 10.0};
  Ribbon ribbon;
  ribbon.pieces.push_back(Piece{{2000, 500}, {2000, 400}, {2040, 400}, {2040, 500}, 0.0, 40.0});
  EXPECT_EQ(ribbon_window(ribbon, grid), Window{});
  ribbon.pieces[0] = Piece{{-400, 500}, {-400, 400}, {-360, 400}, {-360, 500}, 0.0, 40.0};
  EXPECT_EQ(ribbon_window(ribbon, grid), Window{});
  // Its box in world metres and in pixels (rows grow southwards).
  const PieceBox world = piece_box(ribbon.pieces[0]);
  EXPECT_EQ(world.lo, (Vec2{-400, 400}));
  EXPECT_EQ(world.hi, (Vec2{-360, 500}));
  const PieceBox pixels = piece_pixel_box(ribbon.pieces[0], grid);
  EXPECT_EQ(pixels.lo, (Vec2{-40, 30}));
  EXPECT_EQ(pixels.hi, (Vec2{-36, 40}));
  ribbon.pieces[0].top_right = {-350, 520};
  EXPECT_EQ(ribbon_box(ribbon).hi, (Vec2{-350, 520}));
}

// The boxes the caches and the junction finder select inputs with: a NaN coordinate never
// widens a box, an empty box meets nothing, and touching edges meet.
TEST(PointsBox, SkipsNonFiniteCoordinatesAndMeetsAtTouchingEdges) {
  const PieceBox box = points_box({{10.0, 20.0}, {NAN, 5.0}, {30.0, -4.0}});
  EXPECT_EQ(box.lo, (Vec2{10.0, -4.0}));
  EXPECT_EQ(box.hi, (Vec2{30.0, 20.0}));
  EXPECT_FALSE(meets(points_box({}), box));
  EXPECT_FALSE(meets(grown(points_box({}), 1e9), box));
  EXPECT_TRUE(meets(box, PieceBox{{30.0, 20.0}, {31.0, 21.0}}));
  EXPECT_FALSE(meets(box, PieceBox{{30.5, 0.0}, {31.0, 1.0}}));
  EXPECT_TRUE(meets(grown(box, 0.5), PieceBox{{30.5, 0.0}, {31.0, 1.0}}));
  const PieceBox g = grown(box, 2.0);
  EXPECT_EQ(g.lo, (Vec2{8.0, -6.0}));
  EXPECT_EQ(g.hi, (Vec2{32.0, 22.0}));
}

TEST(WorldBox, IsTheWindowsExtentInWorldMetres) {
  const GridSpec grid{100, 80, 1000.0, 2000.0, 2.0, 4.0};
  const PieceBox box = world_box({10, 20, 5, 3}, grid);
  EXPECT_EQ(box.lo, (Vec2{1020.0, 1908.0}));  // column 10, row 23 (the window's south edge)
  EXPECT_EQ(box.hi, (Vec2{1030.0, 1920.0}));  // column 15, row 20
  const PieceBox whole = world_box(Window::whole(grid), grid);
  EXPECT_EQ(whole.lo, (Vec2{1000.0, 1680.0}));
  EXPECT_EQ(whole.hi, (Vec2{1200.0, 2000.0}));
}

TEST(Windows, IntersectAndGrowClampToTheGrid) {
  const GridSpec grid{100, 80, 0.0, 0.0, 1.0, 1.0};
  EXPECT_EQ(intersect({10, 10, 20, 20}, {25, 0, 50, 15}), (Window{25, 10, 5, 5}));
  EXPECT_EQ(intersect({10, 10, 20, 20}, {30, 0, 50, 15}), Window{});
  EXPECT_EQ(grow_window({0, 70, 10, 10}, 3, grid), (Window{0, 67, 13, 13}));
  EXPECT_EQ(grow_window({50, 40, 1, 1}, 1 << 30, grid), Window::whole(grid));
}

TEST(Windows, PointsWindowReachesTheReachPlusTwoPixels) {
  const GridSpec grid{100, 80, 1000.0, 2000.0, 2.0, 2.0};
  // x 1040..1060 -> cols 20..30, y 1960..1950 -> rows 20..25; reach 4 m = 2 px, + 2 px.
  EXPECT_EQ(points_window({{1040.0, 1960.0}, {1060.0, 1950.0}}, 4.0, grid),
            (Window{16, 16, 18, 13}));
  EXPECT_EQ(points_window({{0.0, 0.0}}, 1.0, grid), Window{});  // off the grid
}

// Every item the index returns meets the window, and none that meets it is missed.
TEST(WindowIndex, FindsExactlyTheItemsMeetingAWindow) {
  const GridSpec grid{1000, 700, 0.0, 0.0, 1.0, 1.0};
  std::vector<Window> items;
  for (int i = 0; i < 300; ++i)
    items.push_back(
        {(i * 37) % 990 - 20, (i * 53) % 690 - 10, 1 + (i * 7) % 300, 1 + (i * 11) % 90});
  items.push_back({});  // empty: meets nothing
  const WindowIndex index = index_windows(grid, items, 64);
  for (const Window query : {Window{0, 0, 1000, 700}, Window{100, 100, 64, 64},
                             Window{999, 699, 1, 1}, Window{500, 0, 3, 700}}) {
    std::vector<std::size_t> expected;
    for (std::size_t i = 0; i < items.size(); ++i)
      if (intersect(intersect(items[i], Window::whole(grid)), query).width > 0)
        expected.push_back(i);
    EXPECT_EQ(items_meeting(index, query), expected);
  }
}

}  // namespace
}  // namespace tw
