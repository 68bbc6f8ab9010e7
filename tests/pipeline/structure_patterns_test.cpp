// A pattern synthesized along a bridge stays in its placements: the ground under the bridge
// gets neither its height detail nor its splat (docs/osm.md, "Bridges and tunnels").
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "layers/write.hpp"
#include "pipeline/run.hpp"
#include "synth/placements_io.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPipeline = R"(
version: 1
seed: 5
heightfield: dem.tif
resolution: 10
output: { dir: out, preview: false, geotiff: false }
synthesis_resolution: 1
features:
  roads:
    source: map.gpkg
    layer: roads
    kind: road
    width: 6
    synthesis:
      exemplar: cobble.png
      width: 8
      scale: 5
      delta: 8
      channels: { alpha: splat.cobble, height: height }
)";

TEST(StructurePatterns, ABridgesPatternIsInItsPlacementsButNotOnTheGround) {
  test::TempDir dir;
  test::write_dem(dir / "dem.tif");  // 64 x 64 cells of 10 m from (500000, 5000640)
  // FID 1 on the ground, FID 2 a bridge, 300 m apart.
  test::write_layer(dir / "map.gpkg", "roads",
                    {{"LINESTRING (500050 5000150, 500590 5000150)", 6.0},
                     {"LINESTRING (500050 5000450, 500590 5000450)", 6.0}});
  {
    GDALDataset* gpkg =
        GDALDataset::Open((dir / "map.gpkg").c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE);
    ASSERT_NE(gpkg, nullptr);
    gpkg->ExecuteSQL("ALTER TABLE roads ADD COLUMN bridge TEXT", nullptr, nullptr);
    gpkg->ExecuteSQL("UPDATE roads SET bridge = 'yes' WHERE fid = 2", nullptr, nullptr);
    GDALClose(gpkg);
  }
  const fs::path exemplars = test::source_dir() / "samples/exemplars";
  test::crop_raster(exemplars / "cobble_edging_200x56.png", dir / "cobble.png", "PNG", 60, 56);
  test::crop_raster(exemplars / "cobble_edging_200x56_height.tif", dir / "cobble_height.tif",
                    "GTiff", 60, 56);

  auto run = [&](const std::string& out, std::vector<Override> overrides) {
    overrides.push_back({"output.dir", (dir / out).string()});
    run_pipeline(parse_pipeline(kPipeline, "bridge.yaml", dir.path(), overrides));
    std::ifstream in(dir / out / "report.json");
    return nlohmann::json::parse(in);
  };
  const nlohmann::json with_bridge = run("with", {});
  const nlohmann::json ground_only = run("without", {{"features.roads.where", "fid = 1"}});

  const auto& bridge = with_bridge["classes"][0]["features"][1];
  EXPECT_EQ(bridge["fid"], 2);
  EXPECT_EQ(bridge["structure"], "bridge");
  ASSERT_TRUE(bridge.contains("deck_m"));
  // The bridge's pattern is synthesized and saved ...
  const Synthesis placements = load_placements(
      (dir / "with" / bridge["synthesis"]["placements"].get<std::string>()).string());
  EXPECT_EQ(int(placements.placements.size()), bridge["pieces"].get<int>());
  EXPECT_GT(bridge["pieces"].get<int>(), 10);
  // ... but the heights and splat are those of the run without the bridge, bit for bit (a
  // bridge shapes no ground and paints nothing), while the ground road's pattern is there.
  for (const char* layer : {"height.exr", "splat.exr"}) {
    const ExrContents a = read_exr(dir / "with" / layer);
    const ExrContents b = read_exr(dir / "without" / layer);
    ASSERT_EQ(a.channels, b.channels) << layer;
    for (std::size_t c = 0; c < a.bands.size(); ++c)
      EXPECT_EQ(a.bands[c].pixels, b.bands[c].pixels) << layer << " " << a.channels[c];
  }
  const ExrContents splat = read_exr(dir / "with" / "splat.exr");
  const auto cobble = std::find(splat.channels.begin(), splat.channels.end(), "splat.cobble");
  ASSERT_NE(cobble, splat.channels.end());
  const auto& pixels = splat.bands[std::size_t(cobble - splat.channels.begin())].pixels;
  EXPECT_GT(std::count_if(pixels.begin(), pixels.end(), [](float w) { return w > 0.0f; }), 50);
}

}  // namespace
}  // namespace tw
