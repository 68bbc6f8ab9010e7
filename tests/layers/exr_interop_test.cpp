// EXRs that other tools read (issue #12, item 2): GDAL's georeferencing keys, channel names an
// RGBA reader understands, the GeoTIFF's material order, half floats.
#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfMatrixAttribute.h>
#include <ImfMultiPartInputFile.h>
#include <ImfRgbaFile.h>
#include <ImfStringAttribute.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <array>

#include "layers/write.hpp"
#include "sample_layers.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

TEST(ExrInterop, AnRgbaReaderSeesTheHeightAsLuminance) {
  test::TempDir dir;
  const LayerSet set = test::interop_set();
  const fs::path path = dir / "height.exr";
  write_exr(set, set.layers[0], path, ExrCompression::zip);
  Imf::RgbaInputFile file(path.c_str());
  EXPECT_EQ(file.channels() & Imf::WRITE_Y, Imf::WRITE_Y);
  const auto dw = file.dataWindow();
  ASSERT_EQ(dw.max.x - dw.min.x + 1, 40);
  ASSERT_EQ(dw.max.y - dw.min.y + 1, 30);
  std::vector<Imf::Rgba> pixels(40 * 30);
  file.setFrameBuffer(pixels.data(), 1, 40);
  file.readPixels(dw.min.y, dw.max.y);
  // Half precision: 3 significant digits (0.125 m steps between 128 and 256 m).
  EXPECT_NEAR(float(pixels[7 * 40 + 12].r), 100.0f + 12.0f + 7.0f / 3.0f, 0.07f);
  EXPECT_NEAR(float(pixels[29 * 40 + 39].g), 100.0f + 39.0f + 29.0f / 3.0f, 0.07f);
}

TEST(ExrInterop, SplatMaterialsGoFourByFourIntoRgbaLayersInTheGeoTiffOrder) {
  test::TempDir dir;
  const LayerSet set = test::interop_set();
  const fs::path path = dir / "splat.exr";
  write_exr(set, set.layers[1], path, ExrCompression::none);
  EXPECT_EQ(exr_channel_names(set.layers[1]),
            (std::vector<std::string>{"splat0.R", "splat0.G", "splat0.B", "splat0.A", "splat1.R",
                                      "splat1.G"}));
  // Layer splat1 through the RGBA interface: R is material 4 (bank), G material 5 (crest).
  Imf::RgbaInputFile second(path.c_str(), "splat1");
  std::vector<Imf::Rgba> pixels(40 * 30);
  second.setFrameBuffer(pixels.data(), 1, 40);
  second.readPixels(0, 29);
  for (int c = 0; c < 12; ++c) {
    EXPECT_EQ(float(pixels[c].r), c % 6 == 4 ? 1.0f : 0.0f) << c;
    EXPECT_EQ(float(pixels[c].g), c % 6 == 5 ? 1.0f : 0.0f) << c;
  }
  Imf::RgbaInputFile first(path.c_str(), "splat0");
  first.setFrameBuffer(pixels.data(), 1, 40);
  first.readPixels(0, 29);
  EXPECT_EQ(float(pixels[1].g), 1.0f);  // road, GeoTIFF band 2
  EXPECT_EQ(float(pixels[3].a), 1.0f);  // riverbed, GeoTIFF band 4
  // read_exr gives the bands back in band order under the layer's names.
  const ExrContents back = read_exr(path);
  EXPECT_EQ(back.channels, set.layers[1].channels);
  for (std::size_t m = 0; m < 6; ++m)
    EXPECT_EQ(back.bands[m].pixels, set.layers[1].bands[m].pixels);
}

TEST(ExrInterop, GeoreferencingIsAlsoUnderGdalsOwnKeys) {
  test::TempDir dir;
  const LayerSet set = test::interop_set();
  const fs::path path = dir / "height.exr";
  write_exr(set, set.layers[0], path, ExrCompression::none);
  Imf::InputFile file(path.c_str());
  const auto* wkt = file.header().findTypedAttribute<Imf::StringAttribute>("gdal:crsWkt");
  ASSERT_NE(wkt, nullptr);
  OGRSpatialReference srs, utm;
  ASSERT_EQ(srs.importFromWkt(wkt->value().c_str()), OGRERR_NONE);
  utm.importFromEPSG(32631);
  EXPECT_TRUE(srs.IsSame(&utm));
  const auto* gt = file.header().findTypedAttribute<Imf::M33dAttribute>("gdal:geoTransform");
  ASSERT_NE(gt, nullptr);
  // GDAL's EXR driver reads gt = {m[0][2], m[0][0], m[0][1], m[1][2], m[1][0], m[1][1]}.
  const Imath::M33d& m = gt->value();
  EXPECT_EQ(m[0][2], 500000.0);
  EXPECT_EQ(m[0][0], 10.0);
  EXPECT_EQ(m[0][1], 0.0);
  EXPECT_EQ(m[1][2], 5000300.0);
  EXPECT_EQ(m[1][0], 0.0);
  EXPECT_EQ(m[1][1], -10.0);
}

// Debian 12's GDAL (3.6) is built without its EXR driver (`gdalinfo --formats` lists none), so
// this replays what GDALEXRDataset::Open (OSGeo/gdal frmts/exr/exrdataset.cpp) does with a
// file: a single part (several become subdatasets, georeferencing unread), every header
// attribute dynamic_cast to StringAttribute / M33dAttribute and matched by exact name, the
// geotransform taken as {m[0][2], m[0][0], m[0][1], m[1][2], m[1][0], m[1][1]} (its writer puts
// {0, 0, 1} in the last row), the WKT through importFromWkt, and a channel not named Band<i>
// as the band's description.
TEST(ExrInterop, GdalsEXRDriverWouldReadTheGeoreferencingAsItsOpenDoes) {
  test::TempDir dir;
  const LayerSet set = test::interop_set();
  for (const Layer& layer : set.layers) {
    const fs::path path = dir / (layer.name + ".exr");
    write_exr(set, layer, path, ExrCompression::zip);
    Imf::MultiPartInputFile parts(path.c_str());
    ASSERT_EQ(parts.parts(), 1) << layer.name;
    const Imf::Header& header = parts.header(0);
    int wkts = 0, transforms = 0;
    std::array<double, 6> gt{};
    OGRSpatialReference srs;
    for (auto it = header.begin(); it != header.end(); ++it) {
      const Imf::Attribute* attr = &it.attribute();
      const auto* text = dynamic_cast<const Imf::StringAttribute*>(attr);
      const auto* m33d = dynamic_cast<const Imf::M33dAttribute*>(attr);
      if (text && std::string(it.name()) == "gdal:crsWkt") {
        ++wkts;
        srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        EXPECT_EQ(srs.importFromWkt(text->value().c_str()), OGRERR_NONE);
      } else if (m33d && std::string(it.name()) == "gdal:geoTransform") {
        ++transforms;
        const Imath::M33d& m = m33d->value();
        gt = {m[0][2], m[0][0], m[0][1], m[1][2], m[1][0], m[1][1]};
        EXPECT_EQ(m[2][0], 0.0);
        EXPECT_EQ(m[2][1], 0.0);
        EXPECT_EQ(m[2][2], 1.0);
      }
    }
    EXPECT_EQ(wkts, 1) << layer.name;
    EXPECT_EQ(transforms, 1) << layer.name;
    EXPECT_EQ(gt, set.grid.geotransform()) << layer.name;
    OGRSpatialReference expected;
    ASSERT_EQ(expected.importFromWkt(set.crs_wkt.c_str()), OGRERR_NONE);
    EXPECT_TRUE(srs.IsSame(&expected)) << layer.name;
    // Each channel becomes a band named after it: none reads as GDAL's anonymous "Band<i>".
    int i = 1;
    for (auto c = header.channels().begin(); c != header.channels().end(); ++c, ++i)
      EXPECT_NE(std::string(c.name()), "Band" + std::to_string(i));
  }
}

TEST(ExrInterop, HalfFloatsAreAnOptionAndKeepThreeDigits) {
  test::TempDir dir;
  const LayerSet set = test::interop_set();
  OutputTransaction tx;
  WriteOptions options;
  options.geotiff = false;
  options.preview = false;
  options.exr_pixels = ExrPixels::half;
  write_layer_set(set, dir.path(), tx, options);
  tx.commit();
  Imf::InputFile file((dir / "height.exr").c_str());
  EXPECT_EQ(file.header().channels().findChannel("Y")->type, Imf::HALF);
  const ExrContents back = read_exr(dir / "height.exr");
  const float h = back.bands[0].at(39, 29);
  EXPECT_NE(h, set.layers[0].bands[0].at(39, 29));  // 148.67 has no exact half
  EXPECT_NEAR(h, set.layers[0].bands[0].at(39, 29), 0.07f);
  const ExrContents splat = read_exr(dir / "splat.exr");
  EXPECT_EQ(splat.bands[2].pixels, set.layers[1].bands[2].pixels);  // 0 and 1 are exact
  EXPECT_LT(fs::file_size(dir / "splat.exr"), 6u * 40 * 30 * 2 + 4096);
}

}  // namespace
}  // namespace tw
