// Fold-overs: overdraw by non-adjacent pieces and bow-tie pieces (Zhou et al. 2013, 3.1).
#include "raster/foldover.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gdal_reference.hpp"
#include "raster/rasterize.hpp"

namespace tw {
namespace {

// East along y = +h, a clockwise half-turn of radius h around (100, 0), west along y = -h.
Curve hairpin(double h) {
  Curve c;
  for (int x = 0; x <= 100; x += 5) c.points.push_back({double(x), h});
  for (int k = 1; k < 36; ++k) {
    const double a = std::numbers::pi / 2 - std::numbers::pi * k / 36;
    c.points.push_back({100.0 + h * std::cos(a), h * std::sin(a)});
  }
  for (int x = 100; x >= 0; x -= 5) c.points.push_back({double(x), -h});
  return c;
}

// 0.5 m pixels offset so no centre lies on y = +-2 or on a piece edge.
const GridSpec kGrid{260, 60, -10.13, 15.07, 0.5, 0.5};

std::size_t count_set(const Raster<std::uint8_t>& r) {
  std::size_t n = 0;
  for (auto v : r.pixels) n += v != 0;
  return n;
}

TEST(Foldover, HairpinNarrowerThanTheRibbonFoldsExactlyInTheOverlap) {
  // Legs 6 m apart, ribbon 10 m wide: the legs overlap where |y| < 2.
  const Ribbon ribbon = make_ribbon(hairpin(3.0), {10.0, 2.0});
  const auto mask = foldover_mask(ribbon, kGrid, Window::whole(kGrid));
  std::size_t checked = 0;
  for (int r = 0; r < kGrid.height; ++r)
    for (int c = 0; c < kGrid.width; ++c) {
      const Vec2 p = kGrid.pixel_centre_world(c, r);
      if (p.x < 5.0 || p.x > 95.0) continue;  // straight legs only: away from ends and turn
      EXPECT_EQ(mask.at(c, r), std::abs(p.y) < 2.0 ? 1 : 0) << p.x << "," << p.y;
      ++checked;
    }
  EXPECT_GT(checked, 10000u);
  // The turn (radius 3 m < b/2) folds too, and nothing is flagged outside the ribbon.
  std::size_t at_turn = 0;
  for (int r = 0; r < kGrid.height; ++r)
    for (int c = 0; c < kGrid.width; ++c) {
      if (!mask.at(c, r)) continue;
      const Vec2 p = kGrid.pixel_centre_world(c, r);
      EXPECT_LE(std::abs(p.y), 5.0 + 1e-9);
      EXPECT_LE(p.x, 100.0 + 5.0);
      at_turn += p.x > 97.0;
    }
  EXPECT_GT(at_turn, 20u);
}

TEST(Foldover, GentleArcAndClosedCircleAreEmpty) {
  Curve arc;
  for (int k = 0; k <= 90; ++k) {
    const double a = std::numbers::pi / 2 * k / 90;
    arc.points.push_back({200.0 * std::cos(a) - 150.0, 200.0 * std::sin(a) - 180.0});
  }
  const GridSpec grid{200, 200, -20.0, 30.0, 0.37, 0.41};
  const auto arc_mask = foldover_mask(make_ribbon(arc, {10.0, 3.0}), grid, Window::whole(grid));
  EXPECT_EQ(count_set(arc_mask), 0u);

  Curve circle;
  circle.closed = true;
  for (int k = 0; k < 400; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 400;
    circle.points.push_back({25.0 * std::cos(a) + 12.0, 25.0 * std::sin(a) - 5.0});
  }
  const Ribbon ring = make_ribbon(circle, {8.0, 3.0});
  const auto ring_mask = foldover_mask(ring, grid, Window::whole(grid));
  EXPECT_EQ(count_set(ring_mask), 0u);
  // The footprint itself is there (the mask is empty for the right reason).
  Raster<std::uint8_t> footprint;
  burn_polygons(piece_polygons(ring), grid, Window::whole(grid), footprint, 1);
  EXPECT_GT(count_set(footprint), 5000u);
}

TEST(Foldover, BowTiePieceFlagsItsInvertedLobe) {
  // Right edge BR -> TR crosses the left edge at (0, -1/3); the lobe (TL, P, TR) is inverted.
  Ribbon ribbon;
  ribbon.width = 4.0;
  ribbon.delta = 4.0;
  ribbon.pieces.push_back({{0, 2}, {0, -2}, {4, -2}, {-2, 0.5}, 0.0, 4.0});
  const GridSpec grid{40, 40, -5.03, 5.01, 0.25, 0.25};
  const auto mask = foldover_mask(ribbon, grid, Window::whole(grid));
  Raster<std::uint8_t> lobe;
  burn_polygons({{{{0, 2}, {0, -1.0 / 3.0}, {-2, 0.5}}}}, grid, Window::whole(grid), lobe, 1);
  EXPECT_GT(count_set(lobe), 20u);
  EXPECT_EQ(mask.pixels, lobe.pixels);
}

TEST(Foldover, TilesAreSeamless) {
  const Ribbon ribbon = make_ribbon(hairpin(2.0), {9.0, 1.5});
  const auto whole = foldover_mask(ribbon, kGrid, Window::whole(kGrid));
  for (const Window w : {Window{0, 0, 100, 30}, Window{180, 17, 80, 43}, Window{97, 5, 13, 50}})
    EXPECT_EQ(foldover_mask(ribbon, kGrid, w).pixels, test::crop(whole, w).pixels);
}

}  // namespace
}  // namespace tw
