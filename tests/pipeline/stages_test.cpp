// The middle stages' helpers on extreme input: a ribbon far wider than the grid.
#include "pipeline/detail/stages.hpp"

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
  EXPECT_EQ(detail::ribbon_window(ribbon, grid), (Window{49, 0, 3, 80}));
  ribbon.pieces[0] = Piece{{-5e11, -5e11}, {-5e11, 5e11}, {5e11, 5e11}, {5e11, -5e11}, 0.0, 4.0};
  EXPECT_EQ(detail::ribbon_window(ribbon, grid), Window::whole(grid));
}

}  // namespace
}  // namespace tw
