// Polygon fill against GDAL's rasterizer, seamless tiles, coverage and buffered lines.
#include "raster/rasterize.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <numeric>

#include "core/error.hpp"
#include "gdal_reference.hpp"
#include "shapes.hpp"

namespace tw {
namespace {

// 2.5 m x 2 m pixels (non-square on purpose) over the shapes of shapes.hpp, offset from whole
// metres so no vertex sits on a pixel centre by construction.
GridSpec utm_grid() {
  return {520, 420, 499986.7, 5000800.7, 2.5, 2.0};
}

std::size_t count_set(const Raster<std::uint8_t>& r) {
  return std::size_t(std::count_if(r.pixels.begin(), r.pixels.end(), [](auto v) { return v; }));
}

TEST(BurnPolygons, AgreesWithGdalRasterizeOnRealisticPolygons) {
  const auto polygons = test::realistic_polygons();
  const GridSpec grid = utm_grid();
  Raster<std::uint8_t> ours;
  burn_polygons(polygons, grid, Window::whole(grid), ours, 1);
  const auto gdal = test::gdal_rasterize(polygons, grid);
  ASSERT_EQ(ours.width, grid.width);
  EXPECT_GT(count_set(gdal), 30000u);  // the lake alone is ~ 60 000 pixels
  EXPECT_GE(test::agreement(ours, gdal), 0.999);
  // The islands are holes: the centre of the first one is not filled.
  const Vec2 island = grid.world_to_pixel({500380.0, 5000400.0});
  EXPECT_EQ(ours.at(int(island.x), int(island.y)), 0);
  EXPECT_EQ(gdal.at(int(island.x), int(island.y)), 0);
}

TEST(BurnPolygons, TilesEqualTheCropOfTheWholeGrid) {
  const auto polygons = test::realistic_polygons();
  const GridSpec grid = utm_grid();
  Raster<std::uint8_t> whole;
  burn_polygons(polygons, grid, Window::whole(grid), whole, 1);
  const auto gdal = test::gdal_rasterize(polygons, grid);
  // 128 x 100 tiles with a 7-pixel halo, clipped to the grid: every pixel of every tile matches.
  for (int r0 = 0; r0 < grid.height; r0 += 100) {
    for (int c0 = 0; c0 < grid.width; c0 += 128) {
      const int hc0 = std::max(0, c0 - 7), hr0 = std::max(0, r0 - 7);
      const Window w{hc0, hr0, std::min(grid.width, c0 + 135) - hc0,
                     std::min(grid.height, r0 + 107) - hr0};
      Raster<std::uint8_t> tile;
      burn_polygons(polygons, grid, w, tile, 1);
      ASSERT_EQ(tile.pixels, test::crop(whole, w).pixels) << "tile at " << c0 << "," << r0;
      EXPECT_GE(test::agreement(tile, test::crop(gdal, w)), 0.999);
    }
  }
}

TEST(BurnPolygons, PixelCentreRuleOnAnAxisAlignedSquare) {
  const GridSpec grid{10, 10, 0.0, 10.0, 1.0, 1.0};
  // x in [2.4, 5.6], y in [3.4, 6.2] world; pixel centres x = 2.5..5.5 (cols 2..5);
  // world y of row r's centre is 9.5 - r: rows 4..6 (5.5, 4.5, 3.5).
  const Polygon square{{{2.4, 3.4}, {5.6, 3.4}, {5.6, 6.2}, {2.4, 6.2}}};
  Raster<std::uint8_t> out;
  burn_polygons({square}, grid, Window::whole(grid), out, 7);
  for (int r = 0; r < 10; ++r)
    for (int c = 0; c < 10; ++c) {
      const bool inside = c >= 2 && c <= 5 && r >= 4 && r <= 6;
      EXPECT_EQ(out.at(c, r), inside ? 7 : 0) << c << "," << r;
    }
  EXPECT_EQ(test::agreement(out, test::gdal_rasterize({square}, grid)), 1.0);
}

TEST(BurnPolygons, CentresOnTheBoundaryAreHalfOpenSoNeighboursNeverShare) {
  // Two rectangles sharing an edge through a row of pixel centres (world y = 4.5) and one through
  // a column of centres (world x = 4.5): every centre belongs to exactly one of them. (GDAL
  // instead fills a horizontal edge lying exactly on centres depending on ring orientation.)
  const GridSpec grid{10, 10, 0.0, 10.0, 1.0, 1.0};
  const std::vector<Polygon> parts{{{{1, 1}, {4.5, 1}, {4.5, 4.5}, {1, 4.5}}},
                                   {{{1, 4.5}, {4.5, 4.5}, {4.5, 9}, {1, 9}}},
                                   {{{4.5, 1}, {9, 1}, {9, 9}, {4.5, 9}}}};
  Raster<int> owners(10, 10, 0);
  for (const Polygon& part : parts) {
    Raster<std::uint8_t> mask;
    burn_polygons({part}, grid, Window::whole(grid), mask, 1);
    for (std::size_t i = 0; i < mask.pixels.size(); ++i) owners.pixels[i] += mask.pixels[i];
  }
  for (int r = 0; r < 10; ++r)
    for (int c = 0; c < 10; ++c) {
      const bool inside = c >= 1 && c <= 8 && r >= 1 && r <= 8;  // centres 1.5 .. 8.5
      EXPECT_EQ(owners.at(c, r), inside ? 1 : 0) << c << "," << r;
    }
}

TEST(BurnPolygons, KeepsExistingPixelsAndRejectsWrongSize) {
  const GridSpec grid{8, 8, 0.0, 8.0, 1.0, 1.0};
  Raster<std::uint8_t> out(8, 8, 0);
  out.at(0, 0) = 9;
  burn_polygons({{{{4, 4}, {7, 4}, {7, 7}, {4, 7}}}}, grid, Window::whole(grid), out, 1);
  EXPECT_EQ(out.at(0, 0), 9);
  EXPECT_EQ(out.at(5, 2), 1);
  Raster<std::uint8_t> wrong(3, 3, 0);
  EXPECT_THROW(burn_polygons({}, grid, Window::whole(grid), wrong, 1), Error);
}

TEST(PolygonCoverage, FractionsOnPixelAndHalfPixelEdges) {
  const GridSpec grid{8, 8, 0.0, 8.0, 1.0, 1.0};
  // x in [2, 5.5], y world in [3, 5]: rows 3 and 4 (centres 4.5, 3.5) fully, column 5 half.
  const Polygon rect{{{2, 3}, {5.5, 3}, {5.5, 5}, {2, 5}}};
  const auto cov = polygon_coverage({rect}, grid, Window::whole(grid), 4);
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 8; ++c) {
      float expected = 0.0f;
      if (r == 3 || r == 4) expected = c >= 2 && c <= 4 ? 1.0f : (c == 5 ? 0.5f : 0.0f);
      EXPECT_FLOAT_EQ(cov.at(c, r), expected) << c << "," << r;
    }
  // Two overlapping copies still cover at most 1.
  const auto twice = polygon_coverage({rect, rect}, grid, Window::whole(grid), 4);
  EXPECT_EQ(twice.pixels, cov.pixels);
  EXPECT_THROW(polygon_coverage({rect}, grid, Window::whole(grid), 0), Error);
}

TEST(PolygonCoverage, DiscAreaAndTileSeams) {
  const GridSpec grid{64, 64, 0.0, 64.0, 1.0, 1.0};
  Ring disc;
  for (int k = 0; k < 720; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 720;
    disc.push_back(Vec2{32.3, 31.7} + Vec2{std::cos(a), std::sin(a)} * 20.0);
  }
  const auto cov = polygon_coverage({{disc}}, grid, Window::whole(grid), 8);
  const double area = std::accumulate(cov.pixels.begin(), cov.pixels.end(), 0.0);
  EXPECT_NEAR(area, std::numbers::pi * 400.0, 3.0);  // sampling error of 8x8 per pixel
  const Window tile{17, 5, 30, 41};
  const auto part = polygon_coverage({{disc}}, grid, tile, 8);
  EXPECT_EQ(part.pixels, test::crop(cov, tile).pixels);
}

double segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double t = dot(ab, ab) > 0 ? std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0) : 0.0;
  return distance(p, a + ab * t);
}

TEST(BurnBufferedLines, MatchesBruteForceDistanceToThePolyline) {
  const GridSpec grid{120, 90, 1000.0, 2000.0, 0.5, 0.75};
  const std::vector<std::vector<Vec2>> lines{
      {{1003.1, 1990.2}, {1030.7, 1960.4}, {1041.0, 1985.9}, {1055.3, 1950.1}},
      {{1010.0, 1940.0}},  // a single point: a disc
      {{1000.2, 1999.0}, {1059.0, 1999.9}}};
  const std::vector<double> widths{6.0, 9.0, 1.3};
  Raster<std::uint8_t> out;
  burn_buffered_lines(lines, widths, grid, Window::whole(grid), out, 1);
  std::size_t set = 0;
  for (int r = 0; r < grid.height; ++r)
    for (int c = 0; c < grid.width; ++c) {
      const Vec2 p = grid.pixel_centre_world(c, r);
      double margin = 1e9;  // signed distance to the buffer boundary, smallest over lines
      for (std::size_t l = 0; l < lines.size(); ++l)
        for (std::size_t i = 0; i + 1 < std::max<std::size_t>(2, lines[l].size()); ++i) {
          const Vec2 a = lines[l][i], b = lines[l][std::min(i + 1, lines[l].size() - 1)];
          margin = std::min(margin, segment_distance(p, a, b) - widths[l] / 2.0);
        }
      if (std::abs(margin) < 1e-9) continue;  // on the boundary: either answer is right
      EXPECT_EQ(out.at(c, r), margin < 0 ? 1 : 0) << c << "," << r;
      set += out.at(c, r);
    }
  EXPECT_GT(set, 1500u);
  const Window tile{33, 20, 50, 40};
  Raster<std::uint8_t> part;
  burn_buffered_lines(lines, widths, grid, tile, part, 1);
  EXPECT_EQ(part.pixels, test::crop(out, tile).pixels);
}

TEST(BurnBufferedLines, RejectsMismatchedWidths) {
  const GridSpec grid{4, 4, 0.0, 4.0, 1.0, 1.0};
  Raster<std::uint8_t> out;
  EXPECT_THROW(burn_buffered_lines({{{0, 0}, {1, 1}}}, {}, grid, Window::whole(grid), out, 1),
               Error);
  EXPECT_THROW(burn_buffered_lines({{{0, 0}, {1, 1}}}, {-2.0}, grid, Window::whole(grid), out, 1),
               Error);
}

}  // namespace
}  // namespace tw

namespace tw {
namespace {

TEST(BurnPolygons, SameResultOnOneThreadAndMany) {
  const auto polygons = test::realistic_polygons();
  const GridSpec grid = utm_grid();
  Raster<std::uint8_t> many;
  burn_polygons(polygons, grid, Window::whole(grid), many, 1);
  const auto coverage_many = polygon_coverage(polygons, grid, Window::whole(grid), 3);
  Raster<std::uint8_t> one;
  Raster<float> coverage_one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    burn_polygons(polygons, grid, Window::whole(grid), one, 1);
    coverage_one = polygon_coverage(polygons, grid, Window::whole(grid), 3);
  }
  EXPECT_EQ(one.pixels, many.pixels);
  EXPECT_EQ(coverage_one.pixels, coverage_many.pixels);
}

}  // namespace
}  // namespace tw
