// The preview shows every splat material, the ones a synthesized pattern adds included.
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <set>

#include "layers/detail/hillshade.hpp"
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

// samples/dem.tif (80 x 80 cells of 90 m, the Olinda DEM, samples/README.md) as read by GDAL.
struct Dem {
  Raster<float> heights;
  double cell = 0.0;
};
Dem read_sample_dem() {
  GDALAllRegister();
  const std::string path = (test::source_dir() / "samples/dem.tif").string();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
  EXPECT_TRUE(ds);
  Dem dem{Raster<float>(ds->GetRasterXSize(), ds->GetRasterYSize(), 0.0f), 0.0};
  double t[6];
  ds->GetGeoTransform(t);
  dem.cell = t[1];
  EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, dem.heights.width, dem.heights.height,
                                           dem.heights.pixels.data(), dem.heights.width,
                                           dem.heights.height, GDT_Float32, 0, 0),
            CE_None);
  return dem;
}

// The preview's light is GDAL's hillshade: every pixel of a preview of the sample DEM, all of it
// under one material, is that material's colour times 0.35 + 0.75 x the light GDALDEMProcessing
// ("hillshade", Zevenbergen-Thorne, z 2, edges computed) gives the DEM file itself.
TEST(Preview, ShadesEveryPixelAsGdalDemProcessingDoes) {
  const Dem dem = read_sample_dem();
  const int w = dem.heights.width, h = dem.heights.height;
  LayerSet set;
  set.grid = GridSpec{w, h, 0.0, 0.0, dem.cell, dem.cell};
  set.layers.push_back(height_layer(dem.heights));
  SplatLayers splat;
  splat.materials = {"road"};
  splat.weights = {Raster<float>(w, h, 1.0f)};
  set.layers.push_back(splat_layer(std::move(splat)));
  test::TempDir dir;
  write_preview_png(set, dir / "preview.png");

  const std::string path = (test::source_dir() / "samples/dem.tif").string();
  std::unique_ptr<GDALDataset> src(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
  const char* const args[] = {"-of", "MEM", "-alg",           "ZevenbergenThorne",
                              "-z",  "2",   "-compute_edges", nullptr};
  GDALDEMProcessingOptions* options =
      GDALDEMProcessingOptionsNew(const_cast<char**>(args), nullptr);
  std::unique_ptr<GDALDataset> shaded(GDALDataset::FromHandle(GDALDEMProcessing(
      "", GDALDataset::ToHandle(src.get()), "hillshade", nullptr, options, nullptr)));
  GDALDEMProcessingOptionsFree(options);
  ASSERT_TRUE(shaded);
  std::vector<std::uint8_t> gdal(std::size_t(w) * h);
  ASSERT_EQ(
      shaded->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, w, h, gdal.data(), w, h, GDT_Byte, 0, 0),
      CE_None);

  std::unique_ptr<GDALDataset> png(
      GDALDataset::Open((dir / "preview.png").c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(png);
  std::vector<std::uint8_t> red(std::size_t(w) * h);
  ASSERT_EQ(png->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, w, h, red.data(), w, h, GDT_Byte, 0, 0),
            CE_None);
  const Rgb8 road = preview_material_colour("splat.road");
  int mismatched = 0;
  std::set<int> levels;
  for (std::size_t k = 0; k < gdal.size(); ++k) {
    ASSERT_GE(gdal[k], 1) << "pixel " << k;  // no nodata in the sample
    levels.insert(gdal[k]);
    const double light = 0.35 + 0.75 * (float(gdal[k] - 1) / 254.0f);
    const auto expected = std::uint8_t(std::clamp(float(road[0]) * light, 0.0, 255.0));
    mismatched += red[k] != expected;
  }
  EXPECT_EQ(mismatched, 0);
  EXPECT_GT(levels.size(), 100u);  // real relief: many shades, not a flat test
}

// GDAL's hillshade is the closed form the preview used to compute itself (central differences),
// to GDAL's 254 steps. On the edges GDAL extrapolates the missing neighbour linearly (a one-sided
// difference), where the old code repeated the edge cell (half the slope): edges now shade as
// the interior does.
TEST(Preview, GdalsHillshadeIsTheClosedFormWithinItsSteps) {
  const Dem dem = read_sample_dem();
  const Raster<float>& z = dem.heights;
  const Raster<float> light = detail::hillshade(z, dem.cell, dem.cell);
  const double azimuth = 315.0 * M_PI / 180.0, altitude = 45.0 * M_PI / 180.0;
  double worst = 0.0, worst_corner = 0.0;
  for (int r = 0; r < z.height; ++r)
    for (int c = 0; c < z.width; ++c) {
      const auto at = [&](int cc, int rr) {
        if (cc >= 0 && rr >= 0 && cc < z.width && rr < z.height) return double(z.at(cc, rr));
        return 2.0 * z.at(c, r) - z.at(2 * c - cc, 2 * r - rr);  // extrapolated
      };
      const double dzdx = 2.0 * (at(c + 1, r) - at(c - 1, r)) / (2.0 * dem.cell);
      const double dzdy = 2.0 * (at(c, r - 1) - at(c, r + 1)) / (2.0 * dem.cell);
      const double lit = (-dzdx * std::sin(azimuth) * std::cos(altitude) -
                          dzdy * std::cos(azimuth) * std::cos(altitude) + std::sin(altitude)) /
                         std::sqrt(dzdx * dzdx + dzdy * dzdy + 1.0);
      const bool corner = (c == 0 || c == z.width - 1) && (r == 0 || r == z.height - 1);
      const double d = std::abs(double(light.at(c, r)) - std::clamp(lit, 0.0, 1.0));
      (corner ? worst_corner : worst) = std::max(corner ? worst_corner : worst, d);
    }
  EXPECT_LE(worst, 0.5 / 254.0 + 1e-6);
  EXPECT_LE(worst_corner, 0.05);  // GDAL extrapolates a corner's two missing sides its own way
  // Nodata (and infinities) stay nodata; their neighbours take the cell's own height.
  Raster<float> holes = z;
  holes.at(10, 10) = std::numeric_limits<float>::quiet_NaN();
  holes.at(20, 20) = std::numeric_limits<float>::infinity();
  const Raster<float> with_holes = detail::hillshade(holes, dem.cell, dem.cell);
  EXPECT_TRUE(std::isnan(with_holes.at(10, 10)));
  EXPECT_TRUE(std::isnan(with_holes.at(20, 20)));
  EXPECT_TRUE(std::isfinite(with_holes.at(11, 10)));
  EXPECT_TRUE(std::isfinite(with_holes.at(21, 20)));
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
