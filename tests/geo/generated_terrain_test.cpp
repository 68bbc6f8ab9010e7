#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.hpp"
#include "geo/heightfield.hpp"

namespace tw {
namespace {

GeneratedTerrain small(std::uint64_t seed) {
  GeneratedTerrain params;
  params.width = 96;
  params.height = 64;
  params.pixel_size = 5.0;
  params.feature_size = 160.0;  // hills of 32 pixels: several fit in the window
  params.seed = seed;
  return params;
}

TEST(GenerateHeightfield, SameSeedGivesIdenticalBytes) {
  const Heightfield a = generate_heightfield(small(7));
  const Heightfield b = generate_heightfield(small(7));
  ASSERT_EQ(a.height.pixels.size(), b.height.pixels.size());
  EXPECT_EQ(std::memcmp(a.height.pixels.data(), b.height.pixels.data(),
                        a.height.pixels.size() * sizeof(float)),
            0);
  EXPECT_EQ(a.crs_wkt, b.crs_wkt);
}

TEST(GenerateHeightfield, DifferentSeedsGiveDifferentTerrain) {
  const Heightfield a = generate_heightfield(small(1));
  const Heightfield b = generate_heightfield(small(2));
  int differing = 0;
  for (std::size_t i = 0; i < a.height.pixels.size(); ++i) {
    differing += a.height.pixels[i] != b.height.pixels[i];
  }
  EXPECT_GT(differing, int(a.height.pixels.size()) * 9 / 10);
}

TEST(GenerateHeightfield, GridCrsAndHeightsFollowTheParameters) {
  const GeneratedTerrain params = small(3);
  const Heightfield field = generate_heightfield(params);
  EXPECT_EQ(field.grid, (GridSpec{96, 64, 500000.0, 5000000.0, 5.0, 5.0}));
  EXPECT_EQ(field.height.width, 96);
  EXPECT_EQ(field.height.height, 64);
  EXPECT_EQ(field.source, "generated:seed=3");
  EXPECT_FALSE(field.nodata_value.has_value());
  OGRSpatialReference srs;
  ASSERT_EQ(srs.importFromWkt(field.crs_wkt.c_str()), OGRERR_NONE);
  EXPECT_STREQ(srs.GetAuthorityCode(nullptr), "32631");

  const auto [low, high] =
      std::minmax_element(field.height.pixels.begin(), field.height.pixels.end());
  EXPECT_GE(*low, 0.0f);
  EXPECT_LE(*high, float(params.relief));
  // Real relief, not noise around a constant: a good share of the range is used...
  EXPECT_GT(*high - *low, 0.3 * params.relief);
  // ...and it is smooth: neighbouring pixels differ by far less than the relief.
  double largest_step = 0.0;
  for (int row = 0; row < field.height.height; ++row) {
    for (int col = 1; col < field.height.width; ++col) {
      largest_step = std::max<double>(
          largest_step, std::abs(field.height.at(col, row) - field.height.at(col - 1, row)));
    }
  }
  EXPECT_LT(largest_step, 0.2 * params.relief);
}

TEST(GenerateHeightfield, ATileEqualsTheWindowOfTheLargerWorld) {
  const GeneratedTerrain world = small(6);
  GeneratedTerrain tile = world;
  tile.width = 32;
  tile.height = 24;
  tile.origin_x = world.origin_x + 40 * world.pixel_size;
  tile.origin_y = world.origin_y - 20 * world.pixel_size;
  const Heightfield big = generate_heightfield(world);
  const Heightfield part = generate_heightfield(tile);
  for (int row = 0; row < tile.height; ++row) {
    for (int col = 0; col < tile.width; ++col) {
      ASSERT_EQ(part.height.at(col, row), big.height.at(col + 40, row + 20)) << col << "," << row;
    }
  }
}

TEST(GenerateHeightfield, ReliefScalesHeights) {
  GeneratedTerrain params = small(4);
  const Heightfield base = generate_heightfield(params);
  params.relief *= 2.0;
  const Heightfield doubled = generate_heightfield(params);
  for (std::size_t i = 0; i < base.height.pixels.size(); i += 97) {
    EXPECT_NEAR(doubled.height.pixels[i], 2.0f * base.height.pixels[i], 1e-3);
  }
}

TEST(GenerateHeightfield, BadParametersAreErrors) {
  GeneratedTerrain params = small(5);
  params.crs = "EPSG:4326";
  EXPECT_THROW(generate_heightfield(params), Error);
  params = small(5);
  params.crs = "not a crs";
  EXPECT_THROW(generate_heightfield(params), Error);
  params = small(5);
  params.width = 0;
  EXPECT_THROW(generate_heightfield(params), Error);
  params = small(5);
  params.pixel_size = -1.0;
  EXPECT_THROW(generate_heightfield(params), Error);
  params = small(5);
  params.feature_size = 0.0;
  EXPECT_THROW(generate_heightfield(params), Error);
}

}  // namespace
}  // namespace tw
