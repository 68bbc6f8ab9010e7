// The preview shows every splat material, the ones a synthesized pattern adds included.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "layers/write.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

// A flat 40 x 20 world whose right half is covered by `material` (weight 1), the left half by
// base (channels "splat.base" and "splat.<material>").
LayerSet flat_set_with(const std::string& material) {
  LayerSet set;
  set.grid = GridSpec{40, 20, 500000.0, 5000040.0, 2.0, 2.0};
  set.layers.push_back(height_layer(Raster<float>(40, 20, 100.0f)));
  SplatLayers splat;
  splat.materials = {"base", material};
  splat.weights = {Raster<float>(40, 20, 1.0f), Raster<float>(40, 20, 0.0f)};
  for (int r = 0; r < 20; ++r)
    for (int c = 20; c < 40; ++c)
      splat.weights[0].at(c, r) = 0.0f, splat.weights[1].at(c, r) = 1.0f;
  set.layers.push_back(splat_layer(std::move(splat)));
  return set;
}

Rgb8 pixel(const std::filesystem::path& png_path, int c, int r) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> png(GDALDataset::Open(png_path.c_str(), GDAL_OF_RASTER));
  EXPECT_TRUE(png);
  Rgb8 rgb{};
  for (int b = 0; b < 3; ++b)
    EXPECT_EQ(
        png->GetRasterBand(b + 1)->RasterIO(GF_Read, c, r, 1, 1, &rgb[b], 1, 1, GDT_Byte, 0, 0),
        CE_None);
  return rgb;
}

// Flat ground under a sun 45 degrees up: every colour times 0.35 + 0.75 sin(45 deg).
Rgb8 lit_flat(const Rgb8& colour) {
  const double light = 0.35 + 0.75 * std::sin(M_PI / 4.0);
  Rgb8 out;
  for (int i = 0; i < 3; ++i) out[i] = std::uint8_t(std::min(255.0, colour[i] * light));
  return out;
}

void expect_near(const Rgb8& actual, const Rgb8& expected) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(int(actual[i]), int(expected[i]), 1) << "channel " << i;
}

TEST(Preview, AnExtraMaterialShowsInItsColourWhereItsWeightIsOne) {
  test::TempDir dir;
  const LayerSet set = flat_set_with("lane_paint");
  write_preview_png(set, dir / "preview.png");
  const Rgb8 paint = preview_material_colour("splat.lane_paint");
  expect_near(pixel(dir / "preview.png", 30, 10), lit_flat(paint));
  // The base half keeps the elevation tint, a different colour.
  const Rgb8 base = pixel(dir / "preview.png", 5, 10);
  EXPECT_GT(std::abs(int(base[0]) - int(paint[0])) + std::abs(int(base[1]) - int(paint[1])) +
                std::abs(int(base[2]) - int(paint[2])),
            60);
}

TEST(Preview, TheDemosPatternMaterialsHaveTheirOwnColours) {
  test::TempDir dir;
  write_preview_png(flat_set_with("road_marking"), dir / "marking.png");
  expect_near(pixel(dir / "marking.png", 30, 10),
              lit_flat(preview_material_colour("splat.road_marking")));
  // Markings read pale against the dark road.
  const Rgb8 marking = preview_material_colour("splat.road_marking");
  const Rgb8 road = preview_material_colour("splat.road");
  EXPECT_GT(marking[0] + marking[1] + marking[2], 3 * (road[0] + road[1] + road[2]));
}

TEST(Preview, HalfAWeightShowsHalfTheColour) {
  test::TempDir dir;
  LayerSet set = flat_set_with("lane_paint");
  Layer& splat = set.layers[1];
  const Rgb8 base_only = [&] {
    write_preview_png(set, dir / "full.png");
    return pixel(dir / "full.png", 5, 10);
  }();
  for (int r = 0; r < 20; ++r)
    for (int c = 0; c < 20; ++c) splat.bands[0].at(c, r) = 0.5f, splat.bands[1].at(c, r) = 0.5f;
  write_preview_png(set, dir / "half.png");
  const Rgb8 paint = lit_flat(preview_material_colour("splat.lane_paint"));
  const Rgb8 half = pixel(dir / "half.png", 5, 10);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(int(half[i]), (int(base_only[i]) + int(paint[i])) / 2, 2) << "channel " << i;
}

// Finite but extreme heights (undeclared float nodata, +-3e38) overflow a float difference:
// the tint runs from the lowest to the highest stop all the same, and infinities draw as
// nodata (this crashed on an index of INT_MIN).
TEST(Preview, ExtremeHeightsTintFromLowToHighAndInfinitiesAreNodata) {
  test::TempDir dir;
  LayerSet set;
  set.grid = GridSpec{40, 20, 500000.0, 5000040.0, 2.0, 2.0};
  Raster<float> z(40, 20, -3e38f);
  for (int r = 0; r < 20; ++r)
    for (int c = 20; c < 40; ++c) z.at(c, r) = 3e38f;
  z.at(39, 0) = std::numeric_limits<float>::infinity();
  set.layers.push_back(height_layer(std::move(z)));
  write_preview_png(set, dir / "extreme.png");
  expect_near(pixel(dir / "extreme.png", 5, 10), lit_flat({96, 140, 80}));     // lowest stop
  expect_near(pixel(dir / "extreme.png", 30, 10), lit_flat({225, 215, 200}));  // highest stop
  EXPECT_EQ(pixel(dir / "extreme.png", 39, 0), (Rgb8{40, 40, 40}));
}

TEST(Preview, UnknownMaterialsGetDistinctStableColours) {
  const Rgb8 a = preview_material_colour("splat.boulders");
  const Rgb8 b = preview_material_colour("splat.lane_paint");
  EXPECT_EQ(a, preview_material_colour("splat.boulders"));
  EXPECT_NE(a, b);
  for (const Rgb8& c : {a, b}) {  // saturated: not a grey
    const int spread = std::max({c[0], c[1], c[2]}) - std::min({c[0], c[1], c[2]});
    EXPECT_GT(spread, 100);
  }
}

}  // namespace
}  // namespace tw
