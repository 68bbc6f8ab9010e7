#include "layers/write.hpp"

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "core/error.hpp"
#include "terrain/height_ops.hpp"
#include "terrain/splat.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

WriteOptions only(bool exr, bool geotiff, bool preview) {
  WriteOptions o;
  o.exr = exr;
  o.geotiff = geotiff;
  o.preview = preview;
  return o;
}

std::string utm31_wkt() {
  OGRSpatialReference srs;
  srs.importFromEPSG(32631);
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  std::string out(wkt);
  CPLFree(wkt);
  return out;
}

// A small world: a sloping heightfield with a nodata corner, a road and a river, shaped and
// splatted by the terrain module.
LayerSet sample_set(float tilt = 0.02f) {
  LayerSet set;
  set.grid = GridSpec{160, 120, 500000.0, 5000120.0 * 1.0, 2.0, 2.0};
  set.grid.origin_y = 5000240.0;
  set.crs_wkt = utm31_wkt();
  set.nodata = -9999.0;
  Raster<float> h(set.grid.width, set.grid.height);
  for (int r = 0; r < h.height; ++r)
    for (int c = 0; c < h.width; ++c)
      h.at(c, r) = 200.0f + tilt * c * 2.0f + 6.0f * std::sin(r / 9.0f) * std::cos(c / 13.0f);
  for (int r = 0; r < 15; ++r)
    for (int c = 0; c < 20; ++c) h.at(c, r) = std::numeric_limits<float>::quiet_NaN();
  std::vector<TerrainFeature> features(2);
  features[0].kind = FeatureKind::road;
  features[0].fid = 1;
  features[0].width = 6.0;
  features[0].centerline.points = {
      {500010.0, 5000020.0}, {500150.0, 5000120.0}, {500310.0, 5000140.0}};
  features[1].kind = FeatureKind::river;
  features[1].fid = 2;
  features[1].width = 8.0;
  features[1].centerline.points = {
      {500040.0, 5000230.0}, {500200.0, 5000100.0}, {500300.0, 5000010.0}};
  shape_terrain(h, set.grid, Window::whole(set.grid), features, {});
  set.layers.push_back(height_layer(std::move(h)));
  set.layers.push_back(splat_layer(compute_splat(set.grid, Window::whole(set.grid), features, {})));
  return set;
}

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST(WriteLayers, ExrRoundTripsPixelsAndGeoreferencing) {
  test::TempDir dir;
  const LayerSet set = sample_set();
  OutputTransaction tx;
  WriteOptions options = only(true, false, false);
  options.exr_pixels = ExrPixels::float32;  // exact (automatic stores splat weights as half)
  const auto written = write_layer_set(set, dir.path(), tx, options);
  tx.commit();
  ASSERT_EQ(written.size(), 2u);
  const ExrContents exr = read_exr(dir / "splat.exr");
  EXPECT_EQ(exr.width, set.grid.width);
  EXPECT_EQ(exr.height, set.grid.height);
  EXPECT_EQ(exr.crs_wkt, set.crs_wkt);
  EXPECT_EQ(exr.origin.x, 500000.0);
  EXPECT_EQ(exr.origin.y, 5000240.0);
  EXPECT_EQ(exr.pixel_size.x, 2.0);
  EXPECT_EQ(exr.geotransform, "500000,2,0,5000240,0,-2");
  const Layer& splat = set.layers[1];
  ASSERT_EQ(exr.channels.size(), splat.channels.size());
  for (std::size_t i = 0; i < splat.channels.size(); ++i) {
    const auto it = std::find(exr.channels.begin(), exr.channels.end(), splat.channels[i]);
    ASSERT_NE(it, exr.channels.end()) << splat.channels[i];
    const auto& band = exr.bands[std::size_t(it - exr.channels.begin())];
    EXPECT_EQ(0,
              std::memcmp(band.pixels.data(), splat.bands[i].pixels.data(), band.pixels.size() * 4))
        << splat.channels[i];
  }
  const ExrContents height = read_exr(dir / "height.exr");
  ASSERT_EQ(height.channels, std::vector<std::string>{"height"});
  EXPECT_TRUE(std::isnan(height.bands[0].at(3, 3)));  // nodata stays NaN in the EXR
  EXPECT_EQ(height.bands[0].at(100, 60), set.layers[0].bands[0].at(100, 60));
}

TEST(WriteLayers, EveryExrCompressionKeepsTheExactFloatsAndIsRecordedInTheHeader) {
  test::TempDir dir;
  const LayerSet set = sample_set();
  const struct {
    ExrCompression compression;
    Imf::Compression expected;
  } cases[] = {{ExrCompression::none, Imf::NO_COMPRESSION},
               {ExrCompression::rle, Imf::RLE_COMPRESSION},
               {ExrCompression::zip, Imf::ZIP_COMPRESSION},
               {ExrCompression::zips, Imf::ZIPS_COMPRESSION},
               {ExrCompression::piz, Imf::PIZ_COMPRESSION}};
  std::vector<std::uintmax_t> splat_sizes;
  for (const auto& c : cases) {
    for (const Layer& layer : set.layers) {
      const fs::path path = dir / (layer.name + std::to_string(int(c.expected)) + ".exr");
      write_exr(set, layer, path, c.compression);
      EXPECT_EQ(Imf::InputFile(path.c_str()).header().compression(), c.expected) << path;
      const ExrContents exr = read_exr(path);
      ASSERT_EQ(exr.bands.size(), layer.bands.size());
      for (std::size_t i = 0; i < layer.bands.size(); ++i) {
        const auto it = std::find(exr.channels.begin(), exr.channels.end(), layer.channels[i]);
        ASSERT_NE(it, exr.channels.end()) << layer.channels[i];
        const auto& band = exr.bands[std::size_t(it - exr.channels.begin())];
        EXPECT_EQ(0, std::memcmp(band.pixels.data(), layer.bands[i].pixels.data(),
                                 band.pixels.size() * 4))
            << layer.channels[i] << " " << path;
      }
      if (layer.name == "splat") splat_sizes.push_back(fs::file_size(path));
    }
  }
  // Splat weights are runs of 0 and 1: every codec packs them well below raw floats, and
  // ZIP (automatic's choice for runs) below RLE.
  ASSERT_EQ(splat_sizes.size(), 5u);
  for (std::size_t i = 1; i < splat_sizes.size(); ++i)
    EXPECT_LT(splat_sizes[i], splat_sizes[0] / 2) << i;
  EXPECT_LT(splat_sizes[2], splat_sizes[1]);
}

TEST(WriteLayers, AutomaticPixelsStoreSplatWeightsAsHalfFloatsAndTheRestAsFloat32) {
  test::TempDir dir;
  LayerSet set = sample_set();
  Layer avoidance{"avoidance", {"forbidden", "distance"}, {}};
  avoidance.bands.emplace_back(set.grid.width, set.grid.height, 0.0f);
  avoidance.bands.emplace_back(set.grid.width, set.grid.height, 0.0f);
  for (int r = 0; r < set.grid.height; ++r)
    for (int c = 0; c < set.grid.width; ++c) avoidance.bands[1].at(c, r) = 0.37f * float(c + r);
  set.layers.push_back(avoidance);
  EXPECT_FALSE(exr_half_for(set.layers[0], ExrPixels::automatic));
  EXPECT_TRUE(exr_half_for(set.layers[1], ExrPixels::automatic));
  EXPECT_FALSE(exr_half_for(set.layers[2], ExrPixels::automatic));
  // A tile's layers are named splat_x<i>_y<j>: the channels decide.
  Layer tile = set.layers[1];
  tile.name = "splat_x1_y0";
  EXPECT_TRUE(exr_half_for(tile, ExrPixels::automatic));
  EXPECT_FALSE(exr_half_for(tile, ExrPixels::float32));
  EXPECT_TRUE(exr_half_for(set.layers[0], ExrPixels::half));

  OutputTransaction tx;
  write_layer_set(set, dir.path(), tx, only(true, false, false));  // automatic by default
  tx.commit();
  const auto pixel_type = [&](const std::string& file) {
    const Imf::InputFile in((dir / file).c_str());
    return in.header().channels().begin().channel().type;
  };
  EXPECT_EQ(pixel_type("height.exr"), Imf::FLOAT);
  EXPECT_EQ(pixel_type("splat.exr"), Imf::HALF);
  EXPECT_EQ(pixel_type("avoidance.exr"), Imf::FLOAT);
  // Heights and distances exact; weights within half's rounding (2^-12 below 1), 0 and 1
  // exact, NaN (nodata) still NaN.
  for (const std::string name : {"height", "avoidance"}) {
    const ExrContents exr = read_exr(dir / (name + ".exr"));
    const Layer& layer = *find_layer(set, name);
    for (std::size_t b = 0; b < layer.bands.size(); ++b)
      EXPECT_EQ(0, std::memcmp(exr.bands[b].pixels.data(), layer.bands[b].pixels.data(),
                               layer.bands[b].pixels.size() * 4))
          << name << " " << b;
  }
  const ExrContents splat = read_exr(dir / "splat.exr");
  std::size_t fractional = 0;
  for (std::size_t b = 0; b < set.layers[1].bands.size(); ++b)
    for (std::size_t i = 0; i < splat.bands[b].pixels.size(); ++i) {
      const float written = set.layers[1].bands[b].pixels[i], read = splat.bands[b].pixels[i];
      if (std::isnan(written)) {
        EXPECT_TRUE(std::isnan(read)) << b << " " << i;
        continue;
      }
      if (written == 0.0f || written == 1.0f) {
        ASSERT_EQ(read, written) << b << " " << i;
        continue;
      }
      ++fractional;
      ASSERT_NEAR(read, written, 1.0f / 4096.0f) << b << " " << i;
    }
  EXPECT_GT(fractional, 100u);  // the sample's feature edges blend materials
}

TEST(WriteLayers, AutomaticExrCompressionZipsRunsAndLeavesNoiseRaw) {
  const LayerSet set = sample_set();
  // Smooth heights never repeat exactly: RLE would only cost time.
  EXPECT_EQ(exr_compression_for(set.layers[0]), ExrCompression::none);
  // Splat weights are mostly exact 0 and 1 away from the features.
  EXPECT_EQ(exr_compression_for(set.layers[1]), ExrCompression::zip);
  Layer mask{"mask", {"forbidden"}, {Raster<float>(set.grid.width, set.grid.height, 0.0f)}};
  for (int c = 40; c < 60; ++c) mask.bands[0].at(c, 7) = 1.0f;
  EXPECT_EQ(exr_compression_for(mask), ExrCompression::zip);

  test::TempDir dir;
  OutputTransaction tx;
  write_layer_set(set, dir.path(), tx, only(true, false, false));  // automatic by default
  tx.commit();
  EXPECT_EQ(Imf::InputFile((dir / "height.exr").c_str()).header().compression(),
            Imf::NO_COMPRESSION);
  EXPECT_EQ(Imf::InputFile((dir / "splat.exr").c_str()).header().compression(),
            Imf::ZIP_COMPRESSION);
  EXPECT_EQ(read_exr(dir / "height.exr").bands[0].at(100, 60), set.layers[0].bands[0].at(100, 60));
}

TEST(WriteLayers, GeoTiffTwinIsGeoreferencedWithNamedBandsAndNodata) {
  test::TempDir dir;
  const LayerSet set = sample_set();
  OutputTransaction tx;
  write_layer_set(set, dir.path(), tx, only(false, true, false));
  tx.commit();
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open((dir / "height.tif").c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(ds);
  double gt[6];
  ASSERT_EQ(ds->GetGeoTransform(gt), CE_None);
  const auto expected = set.grid.geotransform();
  for (int i = 0; i < 6; ++i) EXPECT_EQ(gt[i], expected[i]);
  ASSERT_NE(ds->GetSpatialRef(), nullptr);
  OGRSpatialReference utm;
  utm.importFromEPSG(32631);
  EXPECT_TRUE(ds->GetSpatialRef()->IsSame(&utm));
  GDALRasterBand* band = ds->GetRasterBand(1);
  EXPECT_EQ(band->GetRasterDataType(), GDT_Float32);
  EXPECT_STREQ(band->GetDescription(), "height");
  int has_nodata = 0;
  EXPECT_EQ(band->GetNoDataValue(&has_nodata), -9999.0);
  EXPECT_TRUE(has_nodata);
  float corner = 0, inside = 0;
  ASSERT_EQ(band->RasterIO(GF_Read, 3, 3, 1, 1, &corner, 1, 1, GDT_Float32, 0, 0), CE_None);
  ASSERT_EQ(band->RasterIO(GF_Read, 100, 60, 1, 1, &inside, 1, 1, GDT_Float32, 0, 0), CE_None);
  EXPECT_EQ(corner, -9999.0f);
  EXPECT_EQ(inside, set.layers[0].bands[0].at(100, 60));

  std::unique_ptr<GDALDataset> splat(
      GDALDataset::Open((dir / "splat.tif").c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(splat);
  ASSERT_EQ(splat->GetRasterCount(), 6);
  for (int b = 0; b < 6; ++b)
    EXPECT_EQ(splat->GetRasterBand(b + 1)->GetDescription(),
              set.layers[1].channels[std::size_t(b)]);
  // No sidecar files: everything QGIS needs is inside the TIFF.
  for (const auto& entry : fs::directory_iterator(dir.path()))
    EXPECT_TRUE(entry.path().extension() == ".tif") << entry.path();
}

TEST(WriteLayers, PreviewIsAnRgbPngOfTheGridShape) {
  test::TempDir dir;
  const LayerSet set = sample_set();
  OutputTransaction tx;
  WriteOptions options = only(false, false, true);
  options.preview_max_size = 100;  // forces a 2x downsample
  options.preview_lines = {{{500010.0, 5000020.0}, {500150.0, 5000120.0}}};
  write_layer_set(set, dir.path(), tx, options);
  tx.commit();
  GDALAllRegister();
  std::unique_ptr<GDALDataset> png(
      GDALDataset::Open((dir / "preview.png").c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(png);
  EXPECT_EQ(png->GetRasterXSize(), 80);
  EXPECT_EQ(png->GetRasterYSize(), 60);
  EXPECT_EQ(png->GetRasterCount(), 3);
  EXPECT_EQ(png->GetRasterBand(1)->GetRasterDataType(), GDT_Byte);
  // The line's midpoint (500080, 5000070) is drawn in its colour.
  std::uint8_t rgb[3];
  const Vec2 mid = set.grid.world_to_pixel({500080.0, 5000070.0}) / 2.0;
  for (int b = 0; b < 3; ++b)
    ASSERT_EQ(png->GetRasterBand(b + 1)->RasterIO(GF_Read, int(mid.x), int(mid.y), 1, 1, &rgb[b], 1,
                                                  1, GDT_Byte, 0, 0),
              CE_None);
  // Drawn half-transparent in pale yellow: red well above blue whatever lies under it.
  EXPECT_GE(rgb[0], 128);
  EXPECT_GT(int(rgb[0]) - int(rgb[2]), 40);
}

TEST(WriteLayers, AFailingWriteLeavesThePreviousOutputsIntact) {
  test::TempDir dir;
  {
    OutputTransaction tx;
    write_layer_set(sample_set(), dir.path(), tx);
    tx.commit();
  }
  std::map<std::string, std::string> before;
  for (const auto& entry : fs::directory_iterator(dir.path()))
    before[entry.path().filename().string()] = file_bytes(entry.path());
  EXPECT_EQ(before.size(), 5u);  // height/splat .exr + .tif, preview.png

  // A second run whose EXR and GeoTIFF files are written, but whose preview fails (no height
  // layer): the transaction is never committed.
  LayerSet broken = sample_set(0.5f);
  broken.layers.erase(broken.layers.begin());
  EXPECT_THROW(
      {
        OutputTransaction tx;
        write_layer_set(broken, dir.path(), tx);
        tx.commit();
      },
      Error);
  std::map<std::string, std::string> after;
  for (const auto& entry : fs::directory_iterator(dir.path()))
    after[entry.path().filename().string()] = file_bytes(entry.path());
  EXPECT_EQ(before, after);  // same names (no temporaries left), same bytes
}

TEST(WriteLayers, InconsistentLayersNameTheLayer) {
  test::TempDir dir;
  LayerSet set = sample_set();
  set.layers[1].bands.pop_back();
  OutputTransaction tx;
  try {
    write_layer_set(set, dir.path(), tx);
    FAIL() << "expected tw::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'splat'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tw
