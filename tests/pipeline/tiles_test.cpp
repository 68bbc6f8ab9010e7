// Plan once, render tiles (docs/tiles.md): the tile grid, the output.tiles key, and exact tiles:
// every tile file and the VRT mosaic of each layer equal the untiled run bit for bit, on a
// generated world with patterns whose features cross many tile borders and on the demo.
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.hpp"
#include "layers/write.hpp"
#include "pipeline/methods/areas/area_report.hpp"
#include "pipeline/methods/patterns/pattern_report.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/run.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST(TileGrid, CoversTheGridWithClampedHalosWhenTheSizeDoesNotDivideIt) {
  const GridSpec grid{100, 70, 0.0, 0.0, 1.0, 1.0};
  const std::vector<TileSpec> tiles = tile_grid(grid, 32, 4);
  ASSERT_EQ(tiles.size(), 4u * 3u);
  EXPECT_EQ(tiles[0].window, (Window{0, 0, 32, 32}));
  EXPECT_EQ(tiles[0].halo_window, (Window{0, 0, 36, 36}));
  EXPECT_EQ(tiles[5].ix, 1);
  EXPECT_EQ(tiles[5].iy, 1);
  EXPECT_EQ(tiles[5].window, (Window{32, 32, 32, 32}));
  EXPECT_EQ(tiles[5].halo_window, (Window{28, 28, 40, 40}));
  EXPECT_EQ(tiles[11].window, (Window{96, 64, 4, 6}));  // the last column and row are smaller
  EXPECT_EQ(tiles[11].halo_window, (Window{92, 60, 8, 10}));
  std::int64_t cells = 0;
  for (const TileSpec& t : tiles) {
    EXPECT_EQ(t.index, t.iy * 4 + t.ix);
    cells += std::int64_t(t.window.width) * t.window.height;
  }
  EXPECT_EQ(cells, grid.cell_count());
  EXPECT_EQ(tile_file_stem("splat", tiles[11]), "splat_x3_y2");
}

TEST(TileGrid, UntiledIsOneTileAndBadSizesAreErrors) {
  const GridSpec grid{100, 70, 0.0, 0.0, 1.0, 1.0};
  const std::vector<TileSpec> one = tile_grid(grid, 0, 0);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].window, Window::whole(grid));
  EXPECT_EQ(one[0].halo_window, Window::whole(grid));
  EXPECT_THROW(tile_grid(grid, -1, 0), Error);
  EXPECT_THROW(tile_grid(grid, 16, -1), Error);
  EXPECT_THROW(tile_grid(grid, 0, 2), Error);
}

TEST(TilesConfig, KeysAreValidatedWithTheirPath) {
  const std::string base =
      "version: 1\nfeatures: { roads: { source: map.gpkg, kind: road, width: 6 } }\n";
  const auto parse = [&](const std::string& extra) {
    return parse_pipeline(base + extra, "t.yaml", ".");
  };
  const PipelineConfig c = parse("output: { tiles: { size: 512, overlap: 8 } }\n");
  EXPECT_EQ(c.output.tiles.size, 512);
  EXPECT_EQ(c.output.tiles.overlap, 8);
  EXPECT_EQ(parse("").output.tiles.size, 0);
  EXPECT_EQ(parse("").avoidance.max_distance, 500.0);
  EXPECT_EQ(parse("avoidance: { max_distance: 80 }\n").avoidance.max_distance, 80.0);
  const auto message = [&](const std::string& extra) {
    try {
      parse(extra);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message("output: { tiles: { size: 0 } }\n"),
              HasSubstr("output.tiles.size: must be in [1, 16384] pixels, got 0"));
  EXPECT_THAT(message("output: { tiles: { size: 64, overlap: -2 } }\n"),
              HasSubstr("output.tiles.overlap: must be in [0, 4096] pixels, got -2"));
  EXPECT_THAT(message("output: { tiles: { overlap: 2 } }\n"), HasSubstr("output.tiles.size"));
  EXPECT_THAT(message("output: { tiles: { size: 64, halo: 2 } }\n"), HasSubstr("halo"));
  EXPECT_THAT(message("avoidance: { max_distance: 0 }\n"), HasSubstr("avoidance.max_distance"));
}

// Every band of a raster GDAL opens, as float32, band after band.
std::vector<float> gdal_pixels(const fs::path& path, int* width = nullptr, int* height = nullptr) {
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
  if (!ds) {
    ADD_FAILURE() << "GDAL cannot open " << path;
    return {};
  }
  const int w = ds->GetRasterXSize(), h = ds->GetRasterYSize();
  if (width) *width = w;
  if (height) *height = h;
  std::vector<float> pixels(std::size_t(w) * h * ds->GetRasterCount());
  for (int b = 0; b < ds->GetRasterCount(); ++b) {
    EXPECT_EQ(
        ds->GetRasterBand(b + 1)->RasterIO(
            GF_Read, 0, 0, w, h, pixels.data() + std::size_t(w) * h * b, w, h, GDT_Float32, 0, 0),
        CE_None);
  }
  return pixels;
}

// Bitwise: NaN nodata equals NaN nodata, -0 differs from +0.
bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Checks a tiled output folder against an untiled one: the VRT mosaic of every layer, and every
// tile's EXR and GeoTIFF against the same window of the untiled layers (so the overlapping
// pixels of neighbouring tiles are identical too).
void expect_tiles_equal_untiled(const fs::path& untiled, const fs::path& tiled,
                                const std::vector<TileSpec>& tiles) {
  for (const std::string layer : {"height", "splat", "avoidance"}) {
    SCOPED_TRACE(layer);
    int width = 0, height = 0;
    const std::vector<float> whole = gdal_pixels(untiled / (layer + ".tif"), &width, &height);
    EXPECT_TRUE(same_bits(gdal_pixels(tiled / (layer + ".vrt")), whole)) << "the mosaic";
    const ExrContents whole_exr = read_exr(untiled / (layer + ".exr"));
    const std::size_t bands = whole.size() / (std::size_t(width) * height);
    for (const TileSpec& t : tiles) {
      SCOPED_TRACE(tile_file_stem(layer, t));
      const Window& w = t.halo_window;
      std::vector<float> crop;
      for (std::size_t b = 0; b < bands; ++b)
        for (int row = w.row0; row < w.row_end(); ++row) {
          const float* from = whole.data() + (b * height + row) * std::size_t(width) + w.col0;
          crop.insert(crop.end(), from, from + w.width);
        }
      const fs::path stem = tiled / "tiles" / tile_file_stem(layer, t);
      EXPECT_TRUE(same_bits(gdal_pixels(stem.string() + ".tif"), crop));
      const ExrContents exr = read_exr(stem.string() + ".exr");
      ASSERT_EQ(exr.channels, whole_exr.channels);
      ASSERT_EQ(exr.width, w.width);
      for (std::size_t c = 0; c < exr.bands.size(); ++c) {
        std::vector<float> part;
        for (int row = w.row0; row < w.row_end(); ++row) {
          const float* from = &whole_exr.bands[c].at(w.col0, row);
          part.insert(part.end(), from, from + w.width);
        }
        EXPECT_TRUE(same_bits(exr.bands[c].pixels, part)) << exr.channels[c];
      }
    }
  }
}

// A generated world of 200 x 150 cells of 4 m (no size divides it) with roads and a river that
// cross many tiles, a ring road, a lake to avoid, cobble patterns (height and splat), and a
// vineyard (kind: area) that the roads and the river cross.
constexpr const char* kWorld = R"(
version: 1
seed: 5
generate: { width: 200, height: 150, pixel_size: 4, relief: 60 }
output: { dir: out, preview: false }
synthesis_resolution: 1
avoidance: { max_distance: 60 }
existing:
  - { source: map.gpkg, layer: lakes }
features:
  rivers:
    source: map.gpkg
    layer: rivers
    kind: river
    width: 8
    profile: { depth: 2, bank_width: 4, falloff: 12 }
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
  vines:
    kind: area
    source: map.gpkg
    layer: fields
    sketch: vineyard.geojson
    scale: 100
    lead: nearest_road
    materials: { vine: vine_row, post: vine_post }
    height: { vine: 0.3 }
)";

class TiledWorld : public ::testing::Test {
 protected:
  void SetUp() override {
    // The world spans x 500000..500800, y 4999400..5000000.
    test::write_layer(dir_ / "map.gpkg", "roads",
                      {{"LINESTRING (500020 4999450, 500300 4999700, 500780 4999960)"},
                       {"LINESTRING (500100 4999980, 500160 4999700, 500420 4999420)"},
                       {ring(500560, 4999640, 90)}});
    test::write_layer(dir_ / "map.gpkg", "rivers",
                      {{"LINESTRING (500000 4999800, 500250 4999820, 500500 4999520, "
                        "500800 4999500)"}});
    test::write_layer(dir_ / "map.gpkg", "fields",
                      {{"POLYGON ((500180 4999560, 500400 4999560, 500400 4999700, "
                        "500180 4999700, 500180 4999560))"}});
    fs::copy_file(test::source_dir() / "samples/sketches/vineyard.geojson",
                  dir_ / "vineyard.geojson");
    test::write_layer(dir_ / "map.gpkg", "lakes",
                      {{"POLYGON ((500380 4999900, 500460 4999900, 500460 4999960, "
                        "500380 4999960, 500380 4999900))"}});
    const fs::path exemplars = test::source_dir() / "samples/exemplars";
    test::crop_raster(exemplars / "cobble_edging_200x56.png", dir_ / "cobble.png", "PNG", 60, 56);
    test::crop_raster(exemplars / "cobble_edging_200x56_height.tif", dir_ / "cobble_height.tif",
                      "GTiff", 60, 56);
  }

  static std::string ring(double cx, double cy, double r) {
    std::ostringstream wkt;
    wkt.precision(10);
    wkt << "LINESTRING (";
    for (int i = 0; i <= 40; ++i) {
      const double a = 2.0 * M_PI * (i % 40) / 40.0;
      wkt << (i ? ", " : "") << cx + r * std::cos(a) << ' ' << cy + r * std::sin(a);
    }
    wkt << ")";
    return wkt.str();
  }

  PipelineConfig config(const std::string& out, std::vector<Override> overrides = {}) const {
    overrides.push_back({"output.dir", (dir_ / out).string()});
    return parse_pipeline(kWorld, "world.yaml", dir_.path(), overrides);
  }

  test::TempDir dir_;
};

TEST_F(TiledWorld, TheMosaicAndEveryTileEqualTheUntiledRunBitForBit) {
  const RunReport untiled = run_pipeline(config("untiled"));
  const RunReport tiled =
      run_pipeline(config("tiled", {{"output.tiles", "{ size: 37, overlap: 5 }"}}));
  const std::vector<TileSpec> tiles = tile_grid(untiled.grid, 37, 5);
  ASSERT_EQ(tiles.size(), 6u * 5u);
  ASSERT_EQ(tiled.tiles.tiles.size(), tiles.size());
  expect_tiles_equal_untiled(dir_ / "untiled", dir_ / "tiled", tiles);

  // The patterns are there (and cross tiles), placed once for the whole world.
  const ExrContents splat = read_exr(dir_ / "untiled/splat.exr");
  const auto cobble = std::find(splat.channels.begin(), splat.channels.end(), "splat.cobble");
  ASSERT_NE(cobble, splat.channels.end());
  const auto& band = splat.bands[std::size_t(cobble - splat.channels.begin())].pixels;
  EXPECT_GT(std::count_if(band.begin(), band.end(), [](float v) { return v > 0.5f; }), 200);
  for (std::size_t i = 0; i < untiled.classes[1].features.size(); ++i) {
    const FeatureSynthesisReport* synthesis = detail::synthesis_report(untiled, 1, i);
    ASSERT_TRUE(synthesis);
    EXPECT_EQ(file_bytes(dir_ / "untiled" / synthesis->placements),
              file_bytes(dir_ / "tiled" / synthesis->placements));
  }
  EXPECT_EQ(untiled.forbidden_pixels, tiled.forbidden_pixels);
  EXPECT_GT(untiled.forbidden_pixels, 0);

  // The vineyard's rows are in the splat layer (and the same shapes in both runs' vectors).
  const auto rows = std::find(splat.channels.begin(), splat.channels.end(), "splat.vine_row");
  ASSERT_NE(rows, splat.channels.end());
  const auto& row_band = splat.bands[std::size_t(rows - splat.channels.begin())].pixels;
  EXPECT_GT(std::count_if(row_band.begin(), row_band.end(), [](float v) { return v > 0.1f; }), 100);
  ASSERT_EQ(detail::area_reports(untiled).size(), 1u);
  EXPECT_GT(detail::area_reports(untiled)[0].features.at(0).shapes, 20);
  for (const char* file : {"areas.gpkg", "instances.csv", "instances.json"})
    EXPECT_EQ(file_bytes(dir_ / "untiled" / file), file_bytes(dir_ / "tiled" / file)) << file;

  // report.json: the grid of tiles with a hash of each tile's bytes; distinct tiles differ.
  std::ifstream in(dir_ / "tiled/report.json");
  const nlohmann::json json = nlohmann::json::parse(in);
  EXPECT_EQ(json["tiles"]["size"], 37);
  EXPECT_EQ(json["tiles"]["overlap"], 5);
  EXPECT_EQ(json["tiles"]["count"], 30);
  const auto& t7 = json["tiles"]["tiles"][7];
  EXPECT_EQ(t7["ix"], 1);
  EXPECT_EQ(t7["iy"], 1);
  EXPECT_EQ(t7["window"], nlohmann::json({37, 37, 37, 37}));
  EXPECT_EQ(t7["halo_window"], nlohmann::json({32, 32, 47, 47}));
  EXPECT_EQ(t7["xxh64"].get<std::string>().size(), 16u);
  EXPECT_NE(t7["xxh64"], json["tiles"]["tiles"][8]["xxh64"]);
}

// Another tiling of the same world renders the same bytes: a tile equal to the first one of
// another tiling (same window) has the same hash.
TEST_F(TiledWorld, TileHashesDependOnlyOnTheWindowsBytes) {
  const RunReport a = run_pipeline(config("a", {{"output.tiles", "{ size: 64 }"}}));
  const RunReport b = run_pipeline(config("b", {{"output.tiles", "{ size: 64, overlap: 0 }"}}));
  ASSERT_EQ(a.tiles.tiles.size(), b.tiles.tiles.size());
  for (std::size_t i = 0; i < a.tiles.tiles.size(); ++i)
    EXPECT_EQ(a.tiles.tiles[i].xxh64, b.tiles.tiles[i].xxh64);
  const fs::path tiles = dir_ / "a/tiles";
  EXPECT_TRUE(fs::exists(tiles / "height_x3_y2.exr"));
  EXPECT_TRUE(fs::exists(tiles / "avoidance_x3_y2.tif"));
  EXPECT_FALSE(fs::exists(tiles / "height_x4_y0.exr"));  // 200 / 64: four columns
  EXPECT_FALSE(fs::exists(dir_ / "a/height.exr"));       // tiled runs write tiles and mosaics
}

// render_tile holds only its window: each layer is halo-window sized.
TEST_F(TiledWorld, RenderTileReturnsItsHaloWindowOnly) {
  Warnings warnings;
  const WorldPlan plan =
      plan_world(config("p", {{"output.tiles", "{ size: 50, overlap: 3 }"}}), {}, warnings);
  ASSERT_EQ(plan.tiles.size(), 12u);
  const TileSpec& tile = plan.tiles[5];
  const LayerSet set = render_tile(plan, tile);
  EXPECT_EQ(set.grid.width, tile.halo_window.width);
  EXPECT_EQ(set.grid.height, tile.halo_window.height);
  EXPECT_DOUBLE_EQ(set.grid.origin_x, 500000.0 + 4.0 * tile.halo_window.col0);
  EXPECT_DOUBLE_EQ(set.grid.origin_y, 5000000.0 - 4.0 * tile.halo_window.row0);
  for (const Layer& layer : set.layers)
    for (const Raster<float>& band : layer.bands) {
      EXPECT_EQ(band.width, tile.halo_window.width);
      EXPECT_EQ(band.height, tile.halo_window.height);
    }
}

// A region is a window of the world: its layers (untiled, and tiled through the mosaic) are the
// same bytes as that window of the whole run, and only the patterns reaching it are synthesized
// (the north-east corner meets road 1 alone, the first in synthesis order).
TEST_F(TiledWorld, ARegionIsTheSameBytesAsItsWindowOfTheWholeRun) {
  const RunReport whole = run_pipeline(config("whole"));
  const std::string region = "[500702, 4999901, 500800, 5000000]";
  const RunReport part = run_pipeline(config("region", {{"region", region}}));
  const RunReport tiled = run_pipeline(
      config("tiled", {{"region", region}, {"output.tiles", "{ size: 9, overlap: 2 }"}}));
  const Window w{175, 0, 25, 25};  // columns 500700..500800, rows 5000000..4999900
  EXPECT_EQ(part.grid, (GridSpec{25, 25, 500700.0, 5000000.0, 4.0, 4.0}));
  ASSERT_EQ(tiled.tiles.tiles.size(), 9u);
  EXPECT_EQ(tiled.tiles.tiles[4].window, (Window{184, 9, 9, 9}));
  for (const std::string layer : {"height", "splat", "avoidance"}) {
    SCOPED_TRACE(layer);
    int width = 0, height = 0;
    const std::vector<float> all = gdal_pixels(dir_ / "whole" / (layer + ".tif"), &width, &height);
    const std::size_t bands = all.size() / (std::size_t(width) * height);
    std::vector<float> crop;
    for (std::size_t b = 0; b < bands; ++b)
      for (int row = w.row0; row < w.row_end(); ++row) {
        const float* from = all.data() + (b * height + row) * std::size_t(width) + w.col0;
        crop.insert(crop.end(), from, from + w.width);
      }
    EXPECT_TRUE(same_bits(gdal_pixels(dir_ / "region" / (layer + ".tif")), crop));
    EXPECT_TRUE(same_bits(gdal_pixels(dir_ / "tiled" / (layer + ".vrt")), crop)) << "mosaic";
    EXPECT_EQ(read_exr(dir_ / "region" / (layer + ".exr")).channels,
              read_exr(dir_ / "whole" / (layer + ".exr")).channels);
  }
  ASSERT_EQ(part.classes[1].features.size(), 3u);
  ASSERT_TRUE(detail::synthesis_report(part, 1, 0));
  EXPECT_FALSE(detail::synthesis_report(part, 1, 1));  // far from the region, after road 1
  EXPECT_FALSE(detail::synthesis_report(part, 1, 2));
  ASSERT_TRUE(detail::synthesis_report(whole, 1, 0));
  EXPECT_EQ(file_bytes(dir_ / "region" / detail::synthesis_report(part, 1, 0)->placements),
            file_bytes(dir_ / "whole" / detail::synthesis_report(whole, 1, 0)->placements));
  const ExrContents splat = read_exr(dir_ / "region/splat.exr");
  const auto cobble = std::find(splat.channels.begin(), splat.channels.end(), "splat.cobble");
  ASSERT_NE(cobble, splat.channels.end());
  const auto& band = splat.bands[std::size_t(cobble - splat.channels.begin())].pixels;
  EXPECT_GT(std::count_if(band.begin(), band.end(), [](float v) { return v > 0.5f; }), 5);
}

// The demo (a DEM file, ridges, rivers, roads and existing features), tiled 64 with overlap 3
// on a grid of 180 x 180: the same bytes as untiled.
TEST(TiledDemo, TheMosaicEqualsTheUntiledRun) {
  test::TempDir dir;
  const fs::path pipeline = test::source_dir() / "pipelines/demo.yaml";
  const auto demo = [&](const std::string& out, std::vector<Override> overrides) {
    overrides.push_back({"resolution", "40"});
    overrides.push_back({"output.preview", "false"});
    overrides.push_back({"output.dir", (dir.path() / out).string()});
    PipelineConfig config = load_pipeline(pipeline, overrides);
    for (FeatureClassConfig& c : config.features)
      drop_method_options(c.methods, kPatternsMethodName);     // run_test.cpp's demo
    drop_method_options(config.methods, kPatternsMethodName);  // its synthesis_order
    return config;
  };
  const RunReport a = run_pipeline(demo("untiled", {}));
  const RunReport b = run_pipeline(demo("tiled", {{"output.tiles", "{ size: 64, overlap: 3 }"}}));
  expect_tiles_equal_untiled(dir.path() / "untiled", dir.path() / "tiled",
                             tile_grid(a.grid, 64, 3));
  EXPECT_EQ(a.forbidden_pixels, b.forbidden_pixels);
}

}  // namespace
}  // namespace tw
