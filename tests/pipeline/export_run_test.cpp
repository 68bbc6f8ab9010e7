// Engine exports from a run (issue #12): the `export:` key writes them with the run, and
// `terraweave export RUN_DIR` writes the same files from the finished run's GeoTIFFs and
// features.geojson; output keys reach the files (half EXR, compression, COG, provenance).
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
              HasSubstr("unknown engine 'unrael', expected unreal, unity or godot (did you mean "
                        "'unreal'?)"));
  EXPECT_THAT(error("export", "{unreal: {size: 1000}}"),
              HasSubstr("export.unreal.size: unreal takes sizes 127 ... 8129"));
  EXPECT_THAT(error("export", "{unity: {height: r16}}"),
              HasSubstr("only godot takes a height format"));
  EXPECT_THAT(error("output.compress", "jpeg"), HasSubstr("unknown compression 'jpeg'"));
  EXPECT_THAT(error("output.crs", "EPSG:999999"), HasSubstr("PROJ does not know the CRS"));
  const PipelineConfig ok = load_pipeline(dir / "pipeline.yaml", {{"export", "[godot, unity]"}});
  ASSERT_EQ(ok.exports.size(), 2u);
  EXPECT_EQ(ok.exports[0].engine, Engine::godot);
  EXPECT_EQ(ok.output.tiff.predictor, TiffPredictor::floating_point);
  EXPECT_EQ(ok.output.exr_pixels, ExrPixels::half);
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
