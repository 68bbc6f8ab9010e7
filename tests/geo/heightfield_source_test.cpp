#include "geo/heightfield_source.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/error.hpp"
#include "geo/detail/generated_source.hpp"
#include "geo/height_sampler.hpp"
#include "geo/resample.hpp"
#include "geo_test_data.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

using test::DemSpec;
using test::TempDir;

// Bit equality (NaN == NaN) of `window` of `whole` and `part`.
::testing::AssertionResult same_bits(const Raster<float>& whole, const Window& window,
                                     const Raster<float>& part) {
  if (part.width != window.width || part.height != window.height)
    return ::testing::AssertionFailure() << "size " << part.width << " x " << part.height;
  for (int r = 0; r < window.height; ++r)
    for (int c = 0; c < window.width; ++c) {
      const float a = whole.at(window.col0 + c, window.row0 + r), b = part.at(c, r);
      if (std::memcmp(&a, &b, sizeof a) != 0)
        return ::testing::AssertionFailure()
               << "cell (" << window.col0 + c << ", " << window.row0 + r << "): whole " << a
               << ", window " << b;
    }
  return ::testing::AssertionSuccess();
}

// Windows at the corners, the edges, across the middle, single cells and the whole.
std::vector<Window> windows_of(const GridSpec& g) {
  return {{0, 0, g.width, g.height},
          {0, 0, 1, 1},
          {g.width - 1, g.height - 1, 1, 1},
          {g.width / 3, g.height / 4, g.width / 2, g.height / 2},
          {0, g.height / 2, g.width, 3},
          {g.width - 7, 0, 7, g.height},
          {g.width / 2, g.height / 2, g.width - g.width / 2, g.height - g.height / 2}};
}

void expect_windows_match_whole(const HeightfieldSource& source, const Heightfield& whole) {
  ASSERT_EQ(source.grid(), whole.grid);
  for (const Window& w : windows_of(source.grid())) {
    SCOPED_TRACE(::testing::Message()
                 << "window " << w.col0 << "," << w.row0 << " " << w.width << "x" << w.height);
    EXPECT_TRUE(same_bits(whole.height, w, source.read(w)));
  }
}

std::string sample(const char* name) {
  return (test::source_dir() / "samples" / name).string();
}

TEST(HeightfieldSource, NativeWindowsAreTheWholeRead) {
  Warnings warnings;
  const auto source = open_heightfield(sample("dem.tif"), {}, warnings);
  EXPECT_EQ(source->cells_read(), 0);  // opening reads no pixel
  expect_windows_match_whole(*source, read_heightfield(sample("dem.tif")));
  const Window w{10, 20, 30, 5};
  const std::int64_t before = source->cells_read();
  source->read(w);
  EXPECT_EQ(source->cells_read() - before, 150);  // the window, nothing more
}

TEST(HeightfieldSource, ResampledWindowsAreTheWholeRead) {
  for (const Resampling resampling : {Resampling::bilinear, Resampling::cubic}) {
    for (const double resolution : {3.7, 10.0, 41.0}) {
      SCOPED_TRACE(::testing::Message() << "resolution " << resolution << " cubic "
                                        << (resampling == Resampling::cubic));
      HeightfieldOptions options;
      options.resolution = resolution;
      options.resampling = resampling;
      Warnings warnings;
      const auto source = open_heightfield(sample("dem.tif"), options, warnings);
      expect_windows_match_whole(*source, read_heightfield(sample("dem.tif"), options));
    }
  }
}

TEST(HeightfieldSource, WarpedWindowsAreTheWholeRead) {
  for (const Resampling resampling : {Resampling::bilinear, Resampling::cubic}) {
    Warnings warnings;
    HeightfieldOptions options;
    options.resampling = resampling;
    const auto source = open_heightfield(sample("dem_wgs84.tif"), options, warnings);
    expect_windows_match_whole(*source, read_heightfield(sample("dem_wgs84.tif"), options));
  }
}

// Larger than one block of GDAL's warped VRT (512 x 128) and with a nodata hole, so windows
// cross blocks and holes.
TEST(HeightfieldSource, WarpedWindowsCrossBlocks) {
  TempDir dir;
  DemSpec spec;
  spec.width = 700;
  spec.height = 300;
  spec.crs = "EPSG:4326";
  spec.geotransform = {5.9, 0.0005, 0.0, 49.9, 0.0, -0.0005};
  spec.nodata = -9999.0;
  spec.value = [](int c, int r) {
    if (std::hypot(c - 350, r - 150) < 20) return -9999.0;
    return 200.0 + 50.0 * std::sin(c * 0.05) * std::cos(r * 0.07);
  };
  const std::string path = (dir.path() / "geo.tif").string();
  test::write_geotiff(path, spec);
  Warnings warnings;
  const auto source = open_heightfield(path, {}, warnings);
  ASSERT_GT(source->grid().height, 256);
  expect_windows_match_whole(*source, read_heightfield(path));
}

TEST(HeightfieldSource, GeneratedWindowsAreTheGeneratedWorld) {
  GeneratedTerrain params;
  params.width = 300;
  params.height = 200;
  params.pixel_size = 7.5;
  params.seed = 42;
  const auto source = open_generated_heightfield(params);
  expect_windows_match_whole(*source, generate_heightfield(params));
  // A window's own grid sits on the window.
  const Heightfield window = read_heightfield_window(*source, {10, 20, 5, 5});
  EXPECT_DOUBLE_EQ(window.grid.origin_x, params.origin_x + 10 * 7.5);
  EXPECT_DOUBLE_EQ(window.grid.origin_y, params.origin_y - 20 * 7.5);
}

// A plan's generated world opens with the WKT the plan holds (no PROJ lookup): the same cells
// and that WKT, and its other parameters are still checked.
TEST(HeightfieldSource, AGeneratedWorldWithItsCheckedCrsIsTheSameWorld) {
  GeneratedTerrain params;
  params.width = 120;
  params.height = 80;
  params.seed = 9;
  const auto looked_up = open_generated_heightfield(params);
  const auto given = open_generated_heightfield(params, looked_up->crs_wkt());
  EXPECT_FALSE(looked_up->crs_wkt().empty());
  EXPECT_EQ(given->crs_wkt(), looked_up->crs_wkt());
  const Window all = Window::whole(looked_up->grid());
  EXPECT_TRUE(same_bits(looked_up->read(all), all, given->read(all)));
  params.pixel_size = -1.0;
  EXPECT_THROW(open_generated_heightfield(params, looked_up->crs_wkt()), Error);
}

// A tile's render and its report facts ask a generated world for the same window: it is
// computed once (the source keeps the last window) and each caller gets its own copy.
TEST(HeightfieldSource, TheSameGeneratedWindowAgainIsTheSameCopy) {
  GeneratedTerrain params;
  params.width = 300;
  params.height = 200;
  params.seed = 5;
  const auto source = open_generated_heightfield(params);
  const Heightfield whole = generate_heightfield(params);
  const Window tile{40, 30, 120, 90}, other{0, 0, 16, 16};
  Raster<float> first = source->read(tile);
  EXPECT_TRUE(same_bits(whole.height, tile, first));
  first.pixels.assign(first.pixels.size(), -1.0f);  // the caller's copy, not the kept one
  EXPECT_TRUE(same_bits(whole.height, tile, source->read(tile)));
  EXPECT_TRUE(same_bits(whole.height, other, source->read(other)));
  EXPECT_TRUE(same_bits(whole.height, tile, source->read(tile)));
  EXPECT_EQ(detail::generated_cells(*source), 2 * 120 * 90 + 16 * 16);
}

// An untiled world's window (over the copied size) is kept too, and moved out on its second
// read: the noise once per pixel at any size, and the source holds the band only in between.
TEST(HeightfieldSource, ALargeGeneratedWindowIsComputedOnceAndHandedOutOnce) {
  GeneratedTerrain params;
  params.width = 300;
  params.height = 200;
  params.seed = 5;
  const auto source = detail::open_generated_source(params, 100);  // 100 cells are "large"
  const Heightfield whole = generate_heightfield(params);
  const Window window{40, 30, 120, 90};
  const std::int64_t cells = std::int64_t(window.width) * window.height;
  Raster<float> first = source->read(window);
  EXPECT_EQ(detail::generated_cells(*source), cells);
  first.pixels.assign(first.pixels.size(), -1.0f);  // the caller's raster, not the kept one
  EXPECT_TRUE(same_bits(whole.height, window, source->read(window)));
  EXPECT_EQ(detail::generated_cells(*source), cells);  // not computed again
  EXPECT_TRUE(same_bits(whole.height, window, source->read(window)));
  EXPECT_EQ(detail::generated_cells(*source), 2 * cells);  // handed out already: computed again
  EXPECT_EQ(source->cells_read(), 3 * cells);
}

// A HeightSampler over a generated world reads 16 x 16 blocks whatever block it is given: the
// plan computes the cells along its features, not 256 x 256 blocks around them.
TEST(HeightfieldSource, SamplersOfAGeneratedWorldReadSmallBlocks) {
  GeneratedTerrain params;
  params.width = 300;
  params.height = 200;
  params.seed = 5;
  const auto source = open_generated_heightfield(params);
  const Heightfield whole = generate_heightfield(params);
  HeightSampler sampler(*source);
  EXPECT_EQ(sampler.cell(250, 150), whole.height.at(250, 150));
  EXPECT_EQ(sampler.cell(251, 159), whole.height.at(251, 159));  // the same block
  EXPECT_EQ(source->cells_read(), 16 * 16);
  // A file keeps the blocks it is given (a read has a fixed cost).
  Warnings warnings;
  const auto file = open_heightfield(sample("dem.tif"), {}, warnings);
  HeightSampler file_sampler(*file);
  file_sampler.cell(3, 4);
  EXPECT_EQ(file->cells_read(),
            std::int64_t(file->grid().width) * file->grid().height);  // 80^2 < 256^2
}

TEST(HeightfieldSource, WindowOutsideTheGridIsAnError) {
  GeneratedTerrain params;
  params.width = params.height = 64;
  const auto source = open_generated_heightfield(params);
  EXPECT_THROW(source->read({60, 0, 5, 1}), Error);
  EXPECT_THROW(source->read({-1, 0, 5, 1}), Error);
}

// The sampler equals sample_height_bilinear over the whole raster, bit for bit, at points
// on and off the grid and around nodata, whatever the block size and however small the cache.
TEST(HeightSampler, BilinearIsTheWholeRastersBilinear) {
  GeneratedTerrain params;
  params.width = 203;
  params.height = 157;
  params.seed = 3;
  Heightfield field = generate_heightfield(params);
  for (int r = 40; r < 60; ++r)
    for (int c = 70; c < 95; ++c) field.height.at(c, r) = std::nanf("");
  const auto source = in_memory_heightfield(field);
  std::mt19937 random(7);
  const GridSpec& g = field.grid;
  std::uniform_real_distribution<double> x(g.origin_x - 20, g.origin_x + g.width * 10.0 + 20);
  std::uniform_real_distribution<double> y(g.origin_y - g.height * 10.0 - 20, g.origin_y + 20);
  for (const HeightSamplerOptions options :
       {HeightSamplerOptions{}, HeightSamplerOptions{16, 16 * 16 * 4},
        HeightSamplerOptions{7, 1}}) {
    HeightSampler sampler(*source, options);
    for (int i = 0; i < 4000; ++i) {
      const Vec2 p{x(random), y(random)};
      const double expected = sample_height_bilinear(field.height, g, p);
      const double got = sampler.bilinear(p);
      ASSERT_EQ(std::memcmp(&expected, &got, sizeof got), 0)
          << "at " << p.x << ", " << p.y << ": " << expected << " vs " << got;
    }
    EXPECT_LE(sampler.peak_bytes(),
              std::max<std::int64_t>(options.max_bytes, options.block * options.block * 4));
  }
}

}  // namespace
}  // namespace tw
