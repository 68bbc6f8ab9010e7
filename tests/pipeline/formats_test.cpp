// `output.formats` (issue #23 item 1): a run written as EXR only serves every command that
// reads a run (`export`, `view`, `diff`) from its EXRs; the GeoTIFF twins are optional. The EXR
// files read back in OpenImageIO with the float32 heights exact and the half-float splat weights
// within half's rounding of the twin's float32.
#include <OpenImageIO/imageio.h>
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "pipeline/config.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

class Formats : public ::testing::Test {
 protected:
  void SetUp() override {
    write_dem(dir / "dem.tif");  // 64 x 64 cells of 10 m
    write_layer(dir / "map.gpkg", "roads",
                {{"LINESTRING (500100 5000100, 500300 5000300, 500500 5000350)", 6.0}});
    write_layer(dir / "map.gpkg", "rivers",
                {{"LINESTRING (500050 5000600, 500320 5000400, 500600 5000050)", 8.0}});
    std::ofstream(dir / "pipeline.yaml") << R"(version: 1
seed: 1
heightfield: dem.tif
output: { dir: out, preview: false }
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 6 }
  rivers: { source: map.gpkg, layer: rivers, kind: river, width: 8,
            profile: { max_carve: 100 } }
)";
  }
  CommandResult terraweave(const std::string& args) const {
    return run_command("cd '" + dir.path().string() + "' && '" + terraweave_binary().string() +
                       "' " + args + " 2>&1");
  }
  // The data the page of `view` embeds (mesh heights, texture, avoidance mask).
  nlohmann::json page_data(const fs::path& page) const {
    const std::string html = read_file(page);
    const std::string open = R"(<script id="data" type="application/json">)";
    const std::size_t begin = html.find(open) + open.size();
    return nlohmann::json::parse(html.substr(begin, html.find("</script>", begin) - begin));
  }
  TempDir dir;
};

TEST_F(Formats, AnExrOnlyRunIsExportedViewedAndDiffedFromItsExrs) {
  ASSERT_EQ(terraweave("-q run pipeline.yaml --set 'output.formats=[exr]' --set output.dir=exr")
                .exit_code,
            0);
  ASSERT_EQ(terraweave("-q run pipeline.yaml --set output.dir=twins").exit_code, 0);
  for (const char* layer : {"height", "splat", "avoidance"}) {
    EXPECT_TRUE(fs::exists(dir / "exr" / (std::string(layer) + ".exr"))) << layer;
    EXPECT_FALSE(fs::exists(dir / "exr" / (std::string(layer) + ".tif"))) << layer;
    EXPECT_TRUE(fs::exists(dir / "twins" / (std::string(layer) + ".tif"))) << layer;
  }
  // The EXRs are the same bytes with and without twins.
  for (const char* f : {"height.exr", "splat.exr", "avoidance.exr"})
    EXPECT_TRUE(read_file(dir / "exr" / f) == read_file(dir / "twins" / f)) << f;

  // export: the heights are the EXR's float32, so the heightmap is the twins' byte for byte.
  const CommandResult from_exr = terraweave("export exr --to unity --size 65 --out unity_exr");
  ASSERT_EQ(from_exr.exit_code, 0) << from_exr.output;
  ASSERT_EQ(terraweave("export twins --to unity --size 65 --out unity_twins").exit_code, 0);
  EXPECT_EQ(fs::file_size(dir / "unity_exr/heightmap.raw"), 65u * 65u * 2u);
  EXPECT_TRUE(read_file(dir / "unity_exr/heightmap.raw") ==
              read_file(dir / "unity_twins/heightmap.raw"));
  EXPECT_TRUE(fs::exists(dir / "unity_exr/splatmap_0.png"));

  // view: the same mesh and avoidance mask as from the twins; the texture from half weights.
  const CommandResult view = terraweave("view exr --out exr.html");
  ASSERT_EQ(view.exit_code, 0) << view.output;
  ASSERT_EQ(terraweave("view twins --out twins.html").exit_code, 0);
  const nlohmann::json a = page_data(dir / "exr.html"), b = page_data(dir / "twins.html");
  EXPECT_EQ(a["mesh"], b["mesh"]);
  EXPECT_EQ(a["avoidance"], b["avoidance"]);
  EXPECT_EQ(a["texture"]["width"], b["texture"]["width"]);

  // diff: an identical rerun is identical; against the twins' run only the twins differ.
  fs::copy(dir / "exr", dir / "first", fs::copy_options::recursive);
  ASSERT_EQ(terraweave("-q run pipeline.yaml --set 'output.formats=[exr]' --set output.dir=exr")
                .exit_code,
            0);
  const CommandResult same = terraweave("diff first exr");
  EXPECT_EQ(same.exit_code, 0) << same.output;
  EXPECT_THAT(same.output, HasSubstr("identical"));
  const CommandResult other = terraweave("diff exr twins");
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_THAT(other.output, HasSubstr("height.tif: only in B"));
  EXPECT_THAT(other.output, Not(HasSubstr("height.exr")));
  EXPECT_THAT(other.output, Not(HasSubstr("splat.exr")));
}

TEST_F(Formats, TheExrsReadBackInOpenImageIoAsTheGeoTiffTwinsInGdal) {
  ASSERT_EQ(terraweave("-q run pipeline.yaml").exit_code, 0);
  GDALAllRegister();
  for (const char* layer : {"height", "splat", "avoidance"}) {
    const fs::path exr = dir / "out" / (std::string(layer) + ".exr");
    auto in = OIIO::ImageInput::open(exr.string());
    ASSERT_TRUE(in) << exr << ": " << OIIO::geterror();
    const OIIO::ImageSpec spec = in->spec();
    const std::unique_ptr<GDALDataset> tif(
        GDALDataset::Open((dir / "out" / (std::string(layer) + ".tif")).c_str(), GDAL_OF_RASTER));
    ASSERT_TRUE(tif);
    ASSERT_EQ(spec.width, tif->GetRasterXSize());
    ASSERT_EQ(spec.height, tif->GetRasterYSize());
    ASSERT_EQ(spec.nchannels, tif->GetRasterCount()) << layer;
    // Splat weights are stored as half floats, the rest as float32 (automatic).
    EXPECT_EQ(spec.format, std::string(layer) == "splat" ? OIIO::TypeHalf : OIIO::TypeFloat)
        << layer;
    EXPECT_EQ(spec.get_string_attribute("compression"),
              std::string(layer) == "height" ? "none" : "zip")
        << layer;
    std::vector<float> pixels(std::size_t(spec.width) * spec.height * spec.nchannels);
    ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeFloat, pixels.data()));
    const int n = spec.width * spec.height;
    std::size_t fractional = 0;
    for (int b = 0; b < spec.nchannels; ++b) {
      // OIIO orders the channels by the file's (alphabetical) names; the twin's band of the same
      // name. A one-band layer is Y.
      // Splat material i is splat<i/4>.<RGBA[i%4]>.
      const std::string name = spec.channelnames[std::size_t(b)];
      int band = 1;
      for (int t = 1; t <= tif->GetRasterCount(); ++t) {
        const std::string description = tif->GetRasterBand(t)->GetDescription();
        if (name == description + ".Y") band = t;
      }
      if (std::string(layer) == "splat")
        band = 1 + 4 * (name[5] - '0') + int(std::string("RGBA").find(name.back()));
      GDALRasterBand* twin = tif->GetRasterBand(band);
      std::vector<float> expected(static_cast<std::size_t>(n));
      ASSERT_EQ(twin->RasterIO(GF_Read, 0, 0, spec.width, spec.height, expected.data(), spec.width,
                               spec.height, GDT_Float32, 0, 0),
                CE_None);
      int has_nodata = 0;
      const double nodata = twin->GetNoDataValue(&has_nodata);
      for (int i = 0; i < n; ++i) {
        const float e = expected[std::size_t(i)],
                    got = pixels[std::size_t(i) * spec.nchannels + std::size_t(b)];
        if (std::isnan(e) || (has_nodata && e == float(nodata))) {
          ASSERT_TRUE(std::isnan(got)) << layer << " " << name << " " << i;
        } else if (std::string(layer) != "splat" || e == 0.0f || e == 1.0f) {
          ASSERT_EQ(got, e) << layer << " " << name << " " << i;
        } else {
          ++fractional;
          ASSERT_NEAR(got, e, 1.0f / 4096.0f) << layer << " " << name << " " << i;
        }
      }
    }
    if (std::string(layer) == "splat") {
      EXPECT_GT(fractional, 50u);
    }
  }
}

TEST(FormatsConfig, FormatsListTheEncodingsOnceEachAndNotBesideTheOldBooleans) {
  TempDir dir;
  write_layer(dir / "m.gpkg", "roads", {{"LINESTRING (500100 5000100, 500300 5000300)", 6.0}});
  const auto load =
      [&](const std::string& output) {
        std::ofstream(dir / "p.yaml")
            << "version: 1\noutput: " << output
            << "\nfeatures: { r: { source: m.gpkg, layer: roads, kind: road, width: 6 } }\n";
        return load_pipeline(dir / "p.yaml");
      };
  const PipelineConfig exr = load("{ formats: [exr] }");
  EXPECT_TRUE(exr.output.exr);
  EXPECT_FALSE(exr.output.geotiff);
  const PipelineConfig both = load("{ formats: [geotiff, exr], exr_compression: piz }");
  EXPECT_TRUE(both.output.exr && both.output.geotiff);
  EXPECT_EQ(both.output.exr_compression, ExrCompression::piz);
  EXPECT_EQ(both.output.exr_pixels, ExrPixels::automatic);
  EXPECT_EQ(load("{ exr_half: false }").output.exr_pixels, ExrPixels::float32);
  const auto error = [&](const std::string& output) {
    try {
      load(output);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error("{ formats: [exr, tiff] }"), HasSubstr("unknown format 'tiff'"));
  EXPECT_THAT(error("{ formats: [exr, exr] }"), HasSubstr("'exr' given twice"));
  EXPECT_THAT(error("{ formats: [] }"), HasSubstr("expected a list of exr and/or geotiff"));
  EXPECT_THAT(error("{ formats: [exr], geotiff: true }"), HasSubstr("not both"));
  EXPECT_THAT(error("{ exr: false, geotiff: false }"), HasSubstr("no layer format left"));
  EXPECT_THAT(error("{ exr_compression: zstd }"), HasSubstr("unknown EXR compression 'zstd'"));
}

}  // namespace
}  // namespace tw::test
