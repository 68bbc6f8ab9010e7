// Engine exports of tiled runs (issue #12): the whole-world export reads the VRT mosaics and
// equals the untiled run's bit for bit; Unreal World Partition and Unity tiles share their edge
// rows and columns with their neighbours, and one Z scale (the world's min and max) serves all
// tiles: the Unreal tiles put together are the single 505 x 505 heightmap.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/atomic_output.hpp"
#include "pipeline/config.hpp"
#include "pipeline/export_layer_files.hpp"
#include "pipeline/run.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

struct Image {
  int width = 0, height = 0;
  std::vector<double> pixels;  // band 1
  double at(int c, int r) const { return pixels[std::size_t(r) * width + c]; }
};

Image read_image(const fs::path& path) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
  if (!ds) throw std::runtime_error("cannot open " + path.string());
  Image img{ds->GetRasterXSize(), ds->GetRasterYSize(), {}};
  img.pixels.resize(std::size_t(img.width) * img.height);
  if (ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, img.width, img.height, img.pixels.data(),
                                     img.width, img.height, GDT_Float64, 0, 0) != CE_None)
    throw std::runtime_error("cannot read " + path.string());
  return img;
}

Image read_raw16(const fs::path& path, int n) {  // Unity: row 0 of the file is the south edge
  const std::string bytes = test::read_file(path);
  EXPECT_EQ(bytes.size(), std::size_t(n) * n * 2) << path;
  Image img{n, n, std::vector<double>(std::size_t(n) * n)};
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const std::size_t i = (std::size_t(n - 1 - r) * n + c) * 2;
      img.pixels[std::size_t(r) * n + c] =
          std::uint8_t(bytes[i]) | (std::uint16_t(std::uint8_t(bytes[i + 1])) << 8);
    }
  return img;
}

class ExportTiles : public ::testing::Test {
 protected:
  void SetUp() override {
    test::DemSpec dem;  // 300 x 300 cells of 10 m, a nodata hole across tile borders
    dem.width = dem.height = 300;
    dem.origin_y = 5003000.0;
    dem.nodata = -9999.0;
    test::write_dem(dir / "dem.tif", dem);
    {
      GDALAllRegister();
      std::unique_ptr<GDALDataset> ds(
          GDALDataset::Open((dir / "dem.tif").c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE));
      std::vector<float> hole(30 * 20, -9999.0f);
      ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 115, 120, 30, 20, hole.data(), 30, 20,
                                               GDT_Float32, 0, 0),
                CE_None);
    }
    test::write_layer(dir / "map.gpkg", "roads",
                      {{"LINESTRING (500100 5002900, 501300 5001700, 502900 5000300)", 6.0}});
    std::ofstream(dir / "pipeline.yaml") << R"(version: 1
seed: 1
heightfield: dem.tif
output: { dir: out, preview: false, exr: false }
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 6 }
)";
  }
  RunReport run(const std::string& out, std::vector<Override> sets) {
    sets.push_back({"output.dir", (dir / out).string()});
    return run_pipeline(load_pipeline(dir / "pipeline.yaml", sets));
  }
  test::TempDir dir;
};

TEST_F(ExportTiles, WholeWorldExportOfATiledRunEqualsTheUntiledOnes) {
  const std::string exports = "{unreal: {tile_size: 0}, unity: {tile_size: 0}, godot: {}}";
  run("untiled", {{"export", exports}});
  run("tiled", {{"export", exports}, {"output.tiles", "{size: 64, overlap: 2}"}});
  for (const char* f :
       {"unreal/heightmap.png", "unreal/weightmap_base.png", "unreal/weightmap_road.png",
        "unreal/unreal.json", "unreal/splines.csv", "unity/heightmap.raw", "unity/splatmap_0.png",
        "unity/unity.json", "godot/height.exr", "godot/splat_0.png", "godot/godot.json"})
    EXPECT_EQ(test::read_file(dir / "tiled/export" / f),
              test::read_file(dir / "untiled/export" / f))
        << f;
  // The command reads the mosaics the same way.
  const auto cli = test::run_command(
      "'" + test::terraweave_binary().string() + "' export '" + (dir / "tiled").string() +
      "' --to unreal --tile-size 0 --out '" + (dir / "cmd").string() + "'");
  ASSERT_EQ(cli.exit_code, 0) << cli.output;
  EXPECT_EQ(test::read_file(dir / "cmd/heightmap.png"),
            test::read_file(dir / "untiled/export/unreal/heightmap.png"));
}

TEST_F(ExportTiles, WorldPartitionTilesShareEdgesAndOneZScale) {
  // Run tiles of 128: Unreal tiles of 253 (the smallest Epic size holding one), 2 x 2 of them
  // over 300 cells; the single heightmap of the same 505 vertices, for comparison.
  run("tiled",
      {{"export", "{unreal: {}, unity: {}}"}, {"output.tiles", "{size: 128, overlap: 0}"}});
  run("whole", {{"export", "{unreal: {size: 505}}"}});
  const fs::path ue = dir / "tiled/export/unreal";
  const auto sidecar = nlohmann::json::parse(std::ifstream(ue / "unreal.json"));
  EXPECT_EQ(sidecar["tile_size"], 253);
  EXPECT_EQ(sidecar["tiles_x"], 2);
  EXPECT_EQ(sidecar["tiles_y"], 2);
  const Image whole = read_image(dir / "whole/export/unreal/heightmap.png");
  ASSERT_EQ(whole.width, 505);
  for (const std::string layer : {"heightmap", "weightmap_road"}) {
    const Image wl = read_image(dir / "whole/export/unreal" / (layer + ".png"));
    double lo = 65535, hi = 0;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const Image t =
            read_image(ue / (layer + "_x" + std::to_string(i) + "_y" + std::to_string(j) + ".png"));
        ASSERT_EQ(t.width, 253);
        ASSERT_EQ(t.height, 253);
        int differ = 0;
        for (int r = 0; r < 253; ++r)
          for (int c = 0; c < 253; ++c) {
            differ += t.at(c, r) != wl.at(i * 252 + c, j * 252 + r);
            lo = std::min(lo, t.at(c, r));
            hi = std::max(hi, t.at(c, r));
          }
        EXPECT_EQ(differ, 0) << layer << " tile " << i << "," << j;
        if (i == 1) {  // the shared column with the western neighbour
          const Image w = read_image(ue / (layer + "_x0_y" + std::to_string(j) + ".png"));
          for (int r = 0; r < 253; ++r)
            ASSERT_EQ(t.at(0, r), w.at(252, r)) << layer << " row " << r;
        }
        if (j == 1) {  // the shared row with the northern neighbour
          const Image n = read_image(ue / (layer + "_x" + std::to_string(i) + "_y0.png"));
          for (int c = 0; c < 253; ++c)
            ASSERT_EQ(t.at(c, 0), n.at(c, 252)) << layer << " col " << c;
        }
      }
    if (layer == "heightmap") {  // one scale for all: the world's min -> 0, max -> 65535
      EXPECT_EQ(lo, 0.0);
      EXPECT_EQ(hi, 65535.0);
    }
  }
  const auto ws = nlohmann::json::parse(std::ifstream(dir / "whole/export/unreal/unreal.json"));
  EXPECT_EQ(sidecar["scale"], ws["scale"]);
  EXPECT_EQ(sidecar["location_cm"], ws["location_cm"]);

  // Unity: tiles of 129 (2^7 + 1), 3 x 3, named _<x>_<z> with z from the south.
  const fs::path un = dir / "tiled/export/unity";
  const auto us = nlohmann::json::parse(std::ifstream(un / "unity.json"));
  ASSERT_EQ(us["heightmap_resolution"], 129);
  ASSERT_EQ(us["tiles_x"], 3);
  double lo = 65535, hi = 0;
  for (int z = 0; z < 3; ++z)
    for (int x = 0; x < 3; ++x) {
      const auto name = [](int a, int b) {
        return "heightmap_" + std::to_string(a) + "_" + std::to_string(b) + ".raw";
      };
      const Image t = read_raw16(un / name(x, z), 129);  // row 0 = north
      for (double v : t.pixels) lo = std::min(lo, v), hi = std::max(hi, v);
      if (x > 0) {
        const Image w = read_raw16(un / name(x - 1, z), 129);
        for (int r = 0; r < 129; ++r) ASSERT_EQ(t.at(0, r), w.at(128, r)) << x << "," << z;
      }
      if (z > 0) {  // the southern neighbour's north row is this tile's south row
        const Image s = read_raw16(un / name(x, z - 1), 129);
        for (int c = 0; c < 129; ++c) ASSERT_EQ(t.at(c, 128), s.at(c, 0)) << x << "," << z;
      }
      EXPECT_EQ(
          read_image(un / ("splatmap_0_" + std::to_string(x) + "_" + std::to_string(z) + ".png"))
              .width,
          128);
    }
  EXPECT_EQ(lo, 0.0);
  EXPECT_EQ(hi, 65535.0);
}

TEST_F(ExportTiles, TilesReadTheLayerFilesByWindowsOfOneTile) {
  // Unreal tiles of 127 over the 300 cells (run tiles of 64): 3 x 3 tiles of 126 vertex steps,
  // 299 / 378 cells each, so a tile's window spans about 100 cells and the world 300. The
  // world's nodata hole is filled on a copy, which the export reads by windows as well.
  run("tiled", {{"output.tiles", "{size: 64, overlap: 2}"}});
  const fs::path out = dir / "tiled";
  ExportFiles files{out / "height.vrt", out / "splat.vrt", {}};
  EngineExportOptions options;
  options.engine = Engine::unreal;
  options.tile_size = 127;
  const std::int64_t cache_before = GDALGetCacheMax64();
  OutputTransaction tx;
  const EngineExportResult result = export_layer_files(files, {}, options, 64, dir / "ue", tx);
  tx.commit();
  EXPECT_EQ(GDALGetCacheMax64(), cache_before);  // the export's bounded cache is given back
  ASSERT_TRUE(fs::exists(dir / "ue/heightmap_x2_y2.png"));
  // + resample_source_window's margin (a few cells each side)
  const int span = int(std::ceil(126.0 * 299.0 / 378.0)) + 8;
  EXPECT_GT(result.reads.largest_cells, std::int64_t(span - 12) * (span - 12));
  EXPECT_LT(result.reads.largest_cells, 300 * 300 / 6);  // never the world
  EXPECT_LE(result.reads.largest_cells, std::int64_t(span) * span);
  // Two passes over 9 tiles: heights, then heights and the splat's bands again.
  const std::unique_ptr<GDALDataset> splat(
      GDALDataset::Open((out / "splat.vrt").c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(splat);
  EXPECT_GE(result.reads.windows, 9 * (2 + std::int64_t(splat->GetRasterCount())));
}

}  // namespace
}  // namespace tw
