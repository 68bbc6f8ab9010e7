// GeoTIFFs as QGIS users expect them (issue #12, item 3): compression and predictor, overviews,
// COG, nodata on every band, units, material names and provenance; all checked through GDAL.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "layers/write.hpp"
#include "sample_layers.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

std::unique_ptr<GDALDataset> open(const fs::path& path) {
  GDALAllRegister();
  return std::unique_ptr<GDALDataset>(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
}

std::string structure(GDALDataset& ds, const char* key) {
  const char* v = ds.GetMetadataItem(key, "IMAGE_STRUCTURE");
  return v ? v : "";
}

TEST(GeoTiffOptions, CompressionAndPredictorAreRecordedAndLossless) {
  test::TempDir dir;
  const LayerSet set = test::interop_set();
  GeoTiffOptions options;
  options.compression = TiffCompression::deflate;
  options.predictor = TiffPredictor::floating_point;
  write_geotiff(set, set.layers[0], dir / "height.tif", options);
  auto ds = open(dir / "height.tif");
  ASSERT_TRUE(ds);
  EXPECT_EQ(structure(*ds, "COMPRESSION"), "DEFLATE");
  EXPECT_EQ(structure(*ds, "PREDICTOR"), "3");
  std::vector<float> back(40 * 30);
  ASSERT_EQ(
      ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, 40, 30, back.data(), 40, 30, GDT_Float32, 0, 0),
      CE_None);
  EXPECT_EQ(back, set.layers[0].bands[0].pixels);

  options.compression = TiffCompression::lzw;
  options.predictor = TiffPredictor::horizontal;
  write_geotiff(set, set.layers[1], dir / "splat.tif", options);
  EXPECT_EQ(structure(*open(dir / "splat.tif"), "COMPRESSION"), "LZW");
  options.compression = TiffCompression::none;
  write_geotiff(set, set.layers[1], dir / "raw.tif", options);
  EXPECT_EQ(structure(*open(dir / "raw.tif"), "COMPRESSION"), "");
  EXPECT_GT(fs::file_size(dir / "raw.tif"), fs::file_size(dir / "splat.tif"));
}

TEST(GeoTiffOptions, OverviewsAndCogAreReadableWithTheSameFullResolutionPixels) {
  test::TempDir dir;
  const LayerSet set = test::interop_set(600, 520);
  GeoTiffOptions options;
  options.overviews = true;
  write_geotiff(set, set.layers[0], dir / "plain.tif", options);
  auto plain = open(dir / "plain.tif");
  ASSERT_TRUE(plain);
  ASSERT_EQ(plain->GetRasterBand(1)->GetOverviewCount(), 2);  // 300 x 260, 150 x 130
  EXPECT_EQ(plain->GetRasterBand(1)->GetOverview(0)->GetXSize(), 300);
  // AVERAGE of a plane is the plane at the coarse cell centres: cell (0, 0) averages 2 x 2.
  float coarse = 0.0f;
  ASSERT_EQ(plain->GetRasterBand(1)->GetOverview(0)->RasterIO(GF_Read, 0, 0, 1, 1, &coarse, 1, 1,
                                                              GDT_Float32, 0, 0),
            CE_None);
  EXPECT_NEAR(coarse, 100.0f + 0.5f + 0.5f / 3.0f, 1e-4f);

  options = {};
  options.cog = true;
  options.compression = TiffCompression::deflate;
  write_geotiff(set, set.layers[1], dir / "splat.tif", options);
  auto cog = open(dir / "splat.tif");
  ASSERT_TRUE(cog);
  EXPECT_EQ(structure(*cog, "LAYOUT"), "COG");
  EXPECT_EQ(structure(*cog, "COMPRESSION"), "DEFLATE");
  EXPECT_GE(cog->GetRasterBand(1)->GetOverviewCount(), 1);
  ASSERT_EQ(cog->GetRasterCount(), 6);
  for (int b = 0; b < 6; ++b) {
    EXPECT_EQ(cog->GetRasterBand(b + 1)->GetDescription(), set.layers[1].channels[std::size_t(b)]);
    EXPECT_STREQ(cog->GetRasterBand(b + 1)->GetUnitType(), "weight");
  }
  std::vector<float> road(600 * 520);
  ASSERT_EQ(cog->GetRasterBand(2)->RasterIO(GF_Read, 0, 0, 600, 520, road.data(), 600, 520,
                                            GDT_Float32, 0, 0),
            CE_None);
  EXPECT_EQ(road, set.layers[1].bands[1].pixels);
  EXPECT_FALSE(fs::exists(dir / "splat.tif.source.tif"));  // the intermediate is gone
}

TEST(GeoTiffOptions, EveryBandHasNodataUnitsAndProvenance) {
  test::TempDir dir;
  LayerSet set = test::interop_set();
  set.nodata = -9999.0;
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 5; ++c) set.layers[0].bands[0].at(c, r) = std::nanf("");
  // Nodata in every layer (what render_tile does before anything is written): the writer
  // writes the NaN it is given and declares it.
  blank_where_height_is_nodata(set);
  GeoTiffOptions options;
  options.metadata = {{"TERRAWEAVE_VERSION", "9.9.9"}, {"TERRAWEAVE_PIPELINE", "demo.yaml"}};
  write_geotiff(set, set.layers[0], dir / "height.tif", options);
  write_geotiff(set, set.layers[1], dir / "splat.tif", options);
  auto height = open(dir / "height.tif");
  auto splat = open(dir / "splat.tif");
  ASSERT_TRUE(height && splat);
  EXPECT_STREQ(height->GetRasterBand(1)->GetUnitType(), "m");
  EXPECT_STREQ(height->GetMetadataItem("TERRAWEAVE_VERSION"), "9.9.9");
  EXPECT_STREQ(splat->GetMetadataItem("TERRAWEAVE_PIPELINE"), "demo.yaml");
  int has = 0;
  EXPECT_EQ(height->GetRasterBand(1)->GetNoDataValue(&has), -9999.0);
  EXPECT_TRUE(has);
  for (int b = 1; b <= 6; ++b) {
    has = 0;
    EXPECT_TRUE(std::isnan(splat->GetRasterBand(b)->GetNoDataValue(&has)));
    EXPECT_TRUE(has) << b;
    float corner = 0.0f, inside = 0.0f;
    ASSERT_EQ(
        splat->GetRasterBand(b)->RasterIO(GF_Read, 2, 2, 1, 1, &corner, 1, 1, GDT_Float32, 0, 0),
        CE_None);
    ASSERT_EQ(
        splat->GetRasterBand(b)->RasterIO(GF_Read, 10, 10, 1, 1, &inside, 1, 1, GDT_Float32, 0, 0),
        CE_None);
    EXPECT_TRUE(std::isnan(corner)) << b;  // nodata where the height is
    EXPECT_EQ(inside, set.layers[1].bands[std::size_t(b - 1)].at(10, 10)) << b;
  }
}

}  // namespace
}  // namespace tw
