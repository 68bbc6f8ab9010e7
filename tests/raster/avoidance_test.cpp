// The avoidance map is the union of its inputs plus the exact distance to it; junction discs.
#include "raster/avoidance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "gdal_reference.hpp"
#include "raster/distance.hpp"
#include "raster/foldover.hpp"
#include "raster/junction_discs.hpp"
#include "raster/rasterize.hpp"

namespace tw {
namespace {

const GridSpec kGrid{160, 240, 1000.0, 2120.0, 0.5, 0.5};

Raster<std::uint8_t> unite(const Raster<std::uint8_t>& a, const Raster<std::uint8_t>& b) {
  Raster<std::uint8_t> out = a;
  for (std::size_t i = 0; i < out.pixels.size(); ++i)
    out.pixels[i] = (a.pixels[i] | b.pixels[i]) ? 1 : 0;
  return out;
}

AvoidanceInputs sample_inputs(const Ribbon& earlier, const Ribbon& current) {
  AvoidanceInputs in;
  in.polygons = {{{{1010, 2110}, {1030, 2112}, {1025, 2090}, {1008, 2095}}}};
  in.lines = {{{1040, 2115}, {1075, 2070}}};
  in.line_widths = {4.0};
  in.ribbons = {&earlier};
  in.current = &current;
  in.junction_discs = junction_discs({Junction{{1060, 2100}, {}, false}}, {3.0});
  return in;
}

TEST(Avoidance, UnionOfPolygonsLinesRibbonsFoldoversAndDiscs) {
  const Ribbon earlier = make_ribbon(Curve{{{1005, 2010}, {1075, 2030}}, false}, {5.0, 2.0});
  Curve hairpin{
      {{1010, 2050}, {1050, 2050}, {1052, 2049}, {1052, 2047}, {1050, 2046}, {1010, 2046}}, false};
  const Ribbon current = make_ribbon(hairpin, {8.0, 1.0});
  const AvoidanceInputs in = sample_inputs(earlier, current);
  const Window whole = Window::whole(kGrid);
  const AvoidanceMap map = build_avoidance_map(in, kGrid, whole);

  Raster<std::uint8_t> expected(kGrid.width, kGrid.height, 0);
  burn_polygons(in.polygons, kGrid, whole, expected, 1);
  burn_polygons(in.junction_discs, kGrid, whole, expected, 1);
  burn_buffered_lines(in.lines, in.line_widths, kGrid, whole, expected, 1);
  burn_polygons(piece_polygons(earlier), kGrid, whole, expected, 1);
  const auto folds = foldover_mask(current, kGrid, whole);
  std::size_t fold_count = 0;
  for (auto v : folds.pixels) fold_count += v;
  EXPECT_GT(fold_count, 100u);
  expected = unite(expected, folds);
  EXPECT_EQ(map.forbidden.pixels, expected.pixels);
  // The current ribbon's own footprint outside its fold-overs stays free.
  const Vec2 free_px = kGrid.world_to_pixel({1030, 2052.5});
  EXPECT_EQ(map.forbidden.at(int(free_px.x), int(free_px.y)), 0);

  EXPECT_EQ(map.distance.pixels, distance_to_mask(map.forbidden, 0.5, 0.5).pixels);
  for (std::size_t i = 0; i < map.forbidden.pixels.size(); ++i)
    if (map.forbidden.pixels[i]) {
      EXPECT_EQ(map.distance.pixels[i], 0.0f);
    }
  EXPECT_EQ(map.grid, kGrid);
  EXPECT_EQ(map.window, whole);

  const Window tile{40, 30, 70, 50};
  const AvoidanceMap part = build_avoidance_map(in, kGrid, tile);
  EXPECT_EQ(part.forbidden.pixels, test::crop(map.forbidden, tile).pixels);
}

TEST(Avoidance, MismatchedLineWidthsThrow) {
  AvoidanceInputs in;
  in.lines = {{{0, 0}, {1, 1}}};
  EXPECT_THROW(build_avoidance_map(in, kGrid, Window::whole(kGrid)), Error);
}

TEST(JunctionDiscs, CircumscribeTheDisc) {
  const std::vector<Junction> js{{{10, 20}, {}, true}, {{-5, 3}, {}, false}};
  const auto discs = junction_discs(js, {4.0, 0.5}, 16);
  ASSERT_EQ(discs.size(), 2u);
  for (std::size_t j = 0; j < 2; ++j) {
    const double r = j == 0 ? 4.0 : 0.5;
    const Ring& ring = discs[j][0];
    ASSERT_EQ(ring.size(), 16u);
    for (std::size_t k = 0; k < ring.size(); ++k) {
      const Vec2 a = ring[k] - js[j].position, b = ring[(k + 1) % ring.size()] - js[j].position;
      // Distance from the centre to each edge is exactly r: the disc touches every edge.
      EXPECT_NEAR(std::abs(cross(a, b)) / distance(a, b), r, 1e-9);
      EXPECT_GT(cross(a, b), 0.0);  // convex, counter-clockwise
    }
  }
  EXPECT_DOUBLE_EQ(junction_disc_radius({6.0, 10.0, 4.0}, 1.5), 6.5);
  EXPECT_THROW(junction_discs(js, {1.0}), Error);
  EXPECT_THROW(junction_discs(js, {1.0, -1.0}), Error);
}

}  // namespace
}  // namespace tw
