// Engine exports from a run (issue #12): the `export:` key writes them with the run, and
// `terraweave export RUN_DIR` writes the same files from the finished run's GeoTIFFs and
// features.geojson; output keys reach the files (half EXR, compression, COG, provenance).
#include <OpenImageIO/imageio.h>
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "layers/export.hpp"
#include "pipeline/config.hpp"
#include "pipeline/run.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const char* const kPipeline = R"(version: 1
seed: 1
heightfield: dem.tif
output: { dir: out, preview: false, exr_half: true, compress: deflate, predictor: float,
          cog: true }
export: { unreal: {}, unity: { size: 129 } }
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 6 }
  rivers: { source: map.gpkg, layer: rivers, kind: river, width: 8,
            profile: { max_carve: 100 } }
)";

class ExportRun : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_dem(dir / "dem.tif");  // 64 x 64 cells of 10 m
    test::write_layer(dir / "map.gpkg", "roads",
                      {{"LINESTRING (500100 5000100, 500300 5000300, 500500 5000350)", 6.0}});
    test::write_layer(dir / "map.gpkg", "rivers",
                      {{"LINESTRING (500050 5000600, 500320 5000400, 500600 5000050)", 8.0}});
    std::ofstream(dir / "pipeline.yaml") << kPipeline;
  }
  test::TempDir dir;
};

TEST_F(ExportRun, TheExportKeyWritesEachEngineAndTheCommandTheSameFilesFromTheRun) {
  const RunReport report = run_pipeline(load_pipeline(dir / "pipeline.yaml"));
  const fs::path out = dir / "out";
  for (const char* f : {"export/unreal/heightmap.png", "export/unreal/unreal.json",
                        "export/unreal/weightmap_road.png", "export/unreal/splines.csv",
                        "export/unity/heightmap.raw", "export/unity/splatmap_0.png",
                        "export/unity/splatmap_1.png", "features.geojson"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_EQ(fs::file_size(out / "export/unity/heightmap.raw"), 129u * 129u * 2u);
  const auto ue = nlohmann::json::parse(std::ifstream(out / "export/unreal/unreal.json"));
  EXPECT_EQ(ue["size"][0], 127);  // 64 cells: Epic's smallest size
  // The splines are the two lines, with the terrain's heights under their points.
  const auto splines = nlohmann::json::parse(std::ifstream(out / "export/unreal/splines.json"));
  ASSERT_EQ(splines["splines"].size(), 2u);
  EXPECT_EQ(splines["splines"][1]["kind"], "river");
  EXPECT_EQ(splines["splines"][1]["width"].get<double>(), 800.0);

  // The command reads the finished run: the same Unreal files, byte for byte.
  const auto cli =
      test::run_command("'" + test::terraweave_binary().string() + "' export '" + out.string() +
                        "' --to unreal --out '" + (dir / "ue").string() + "'");
  ASSERT_EQ(cli.exit_code, 0) << cli.output;
  EXPECT_THAT(cli.output, HasSubstr("unreal: Scale X 500.0000 Y 500.0000 Z"));
  for (const char* f :
       {"heightmap.png", "weightmap_base.png", "weightmap_road.png", "splines.json", "splines.csv"})
    EXPECT_EQ(test::read_file(dir / "ue" / f), test::read_file(out / "export/unreal" / f)) << f;

  // The output keys reached the files.
  GDALAllRegister();
  std::unique_ptr<GDALDataset> tif(GDALDataset::Open((out / "height.tif").c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(tif);
  EXPECT_STREQ(tif->GetMetadataItem("LAYOUT", "IMAGE_STRUCTURE"), "COG");
  EXPECT_STREQ(tif->GetMetadataItem("COMPRESSION", "IMAGE_STRUCTURE"), "DEFLATE");
  EXPECT_STREQ(tif->GetMetadataItem("TERRAWEAVE_PIPELINE"), "pipeline.yaml");
  EXPECT_NE(
      std::find(report.outputs.begin(), report.outputs.end(), out / "export/unreal/heightmap.png"),
      report.outputs.end());
}

TEST_F(ExportRun, BadExportAndOutputKeysNameTheKey) {
  const auto error = [&](const std::string& key, const std::string& value) {
    try {
      load_pipeline(dir / "pipeline.yaml", {{key, value}});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error("export", "[unrael]"),
              HasSubstr("unknown engine 'unrael', expected unreal, unity, godot or terrain3d "
                        "(did you mean 'unreal'?)"));
  EXPECT_THAT(error("export", "{unreal: {size: 5}}"),
              HasSubstr("export.unreal.size: unreal takes sizes 8 ... 8129 (Epic's recommended"));
  EXPECT_THAT(error("export", "{unity: {size: 1000}}"),
              HasSubstr("export.unity.size: unity takes sizes 33 ... 4097 (2^n + 1), not 1000"));
  EXPECT_THAT(error("export", "{unity: {height: r16}}"),
              HasSubstr("only godot and terrain3d take a height format"));
  EXPECT_THAT(error("export", "{terrain3d: {tile_size: 505}}"),
              HasSubstr("terrain3d takes one heightmap, not tiles"));
  EXPECT_THAT(error("export", "{unreal: {layers: true, tile_size: 505}}"),
              HasSubstr("layers are written with one heightmap"));
  EXPECT_EQ(
      load_pipeline(dir / "pipeline.yaml", {{"export", "{unreal: {size: 1000}}"}}).exports[0].size,
      1000);
  EXPECT_THAT(error("output.compress", "jpeg"), HasSubstr("unknown compression 'jpeg'"));
  EXPECT_THAT(error("output.crs", "EPSG:999999"), HasSubstr("PROJ does not know the CRS"));
  const PipelineConfig ok = load_pipeline(dir / "pipeline.yaml", {{"export", "[godot, unity]"}});
  ASSERT_EQ(ok.exports.size(), 2u);
  EXPECT_EQ(ok.exports[0].engine, Engine::godot);
  EXPECT_EQ(ok.output.tiff.predictor, TiffPredictor::floating_point);
  EXPECT_EQ(ok.output.exr_pixels, ExrPixels::half);
}

// Terrain3D and the non-destructive layers from a run: the `export:` key (the run's own input
// heights) and the command with --input-height (the DEM the pipeline read) write the same
// height delta, and it is height.tif - dem.tif at every sampled cell. The command takes a
// non-recommended Unreal size.
TEST_F(ExportRun, Terrain3DAndLayersFromTheKeyAndFromTheCommandWithTheInputDem) {
  const PipelineConfig config = load_pipeline(
      dir / "pipeline.yaml", {{"export", "{terrain3d: {layers: true}, unreal: {layers: true}}"}});
  run_pipeline(config);
  const fs::path out = dir / "out";
  for (const char* f :
       {"export/terrain3d/height.exr", "export/terrain3d/control.exr",
        "export/terrain3d/terrain3d.json", "export/terrain3d/import_terrain3d.gd",
        "export/terrain3d/layers/height_delta.exr", "export/terrain3d/layers/weight_road.png",
        "export/unreal/layers/height_delta.png", "export/unreal/layers/weight_riverbed.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto cli =
      test::run_command("'" + test::terraweave_binary().string() + "' export '" + out.string() +
                        "' --to terrain3d --input-height '" + (dir / "dem.tif").string() +
                        "' --out '" + (dir / "t3d").string() + "'");
  ASSERT_EQ(cli.exit_code, 0) << cli.output;
  EXPECT_THAT(cli.output, HasSubstr("terrain3d: import position (0, 0)"));
  for (const char* f : {"height.exr", "control.exr", "layers/height_delta.exr",
                        "layers/weight_road.png", "import_terrain3d.gd", "splines.json"})
    EXPECT_EQ(test::read_file(dir / "t3d" / f), test::read_file(out / "export/terrain3d" / f)) << f;
  // (terrain3d.json differs by the WKT spelling: the plan's and the GeoTIFF's.)
  const auto t3d = nlohmann::json::parse(std::ifstream(dir / "t3d/terrain3d.json"));
  EXPECT_EQ(t3d["region_size"], 256);
  EXPECT_EQ(t3d["size"][0], 64);
  // The delta against the two GeoTIFFs.
  GDALAllRegister();
  const auto band = [](const fs::path& path) {
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
    std::vector<float> v(std::size_t(ds->GetRasterXSize()) * ds->GetRasterYSize());
    EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, ds->GetRasterXSize(),
                                             ds->GetRasterYSize(), v.data(), ds->GetRasterXSize(),
                                             ds->GetRasterYSize(), GDT_Float32, 0, 0),
              CE_None);
    return v;
  };
  const std::vector<float> result = band(out / "height.tif"), input = band(dir / "dem.tif");
  std::vector<float> delta(64 * 64);
  {
    auto exr = OIIO::ImageInput::open((dir / "t3d/layers/height_delta.exr").string());
    ASSERT_TRUE(exr);
    ASSERT_EQ(exr->spec().width, 64);
    ASSERT_TRUE(exr->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, delta.data()));
  }
  ASSERT_EQ(delta.size(), 64u * 64u);
  int changed = 0;
  for (std::size_t i = 0; i < delta.size(); i += 7) {
    ASSERT_EQ(delta[i], result[i] - input[i]) << i;
    changed += delta[i] != 0.0f;
  }
  EXPECT_GT(changed, 10);  // the river's bed and the road's grading

  const auto sized =
      test::run_command("'" + test::terraweave_binary().string() + "' export '" + out.string() +
                        "' --to unreal --size 1000 --out '" + (dir / "ue1000").string() + "'");
  ASSERT_EQ(sized.exit_code, 0) << sized.output;
  EXPECT_THAT(sized.output, HasSubstr("1000 is not one of Epic's recommended sizes"));
  EXPECT_THAT(sized.output, HasSubstr("(1000 x 1000) as a landscape"));
}

TEST_F(ExportRun, TheCommandNamesWhatARunFolderLacks) {
  const auto cli =
      test::run_command("'" + test::terraweave_binary().string() + "' export '" +
                        dir.path().string() + "' --to godot --out '" + (dir / "g").string() + "'");
  EXPECT_EQ(cli.exit_code, 1);
  EXPECT_THAT(cli.output, HasSubstr("not a finished run (no report.json)"));
  EXPECT_FALSE(fs::exists(dir / "g"));
}

}  // namespace
}  // namespace tw
