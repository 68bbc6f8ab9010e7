// Engine exports, issue #22 items 4 and 5: Terrain3D (its packed control map decodes back to
// the dominant materials and their blend), square pixels for every engine on a non-square
// world (X spacing == Y spacing, the world padded, never stretched), any Unreal size, and the
// non-destructive layers (height delta = result - input, weight layers summing to the splat).
#include <OpenImageIO/imageio.h>
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "layers/export.hpp"
#include "layers/write.hpp"
#include "sample_layers.hpp"
#include "test_support.hpp"

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

// A one-channel float EXR as written (Terrain3D's heights, control bits, height deltas).
std::vector<float> read_exr(const fs::path& path, int& width, int& height) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw std::runtime_error("cannot open " + path.string());
  const OIIO::ImageSpec spec = in->spec();
  EXPECT_EQ(spec.nchannels, 1);
  EXPECT_EQ(spec.channelnames[0], "R");
  EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
  width = spec.width;
  height = spec.height;
  std::vector<float> out(std::size_t(width) * height);
  if (!in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, out.data()))
    throw std::runtime_error("cannot read " + path.string());
  return out;
}

nlohmann::json read_json(const fs::path& path) {
  return nlohmann::json::parse(std::ifstream(path));
}

EngineExportResult run_export(const LayerSet& set, EngineExportOptions options, const fs::path& dir,
                              const Raster<float>* input = nullptr) {
  OutputTransaction tx;
  EngineExportResult result = export_for_engine(set, {}, options, dir, tx, input);
  tx.commit();
  return result;
}

// Three materials whose weights vary per cell: base falls west to east, road rises, bank is
// 0.3 on odd rows: every order of the three, ties and single materials occur.
LayerSet mixed_set(int w, int h) {
  LayerSet set = test::interop_set(w, h);
  SplatLayers splat;
  splat.materials = {"base", "road", "bank"};
  for (int m = 0; m < 3; ++m) splat.weights.emplace_back(w, h, 0.0f);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const float t = float(c) / float(w - 1);
      splat.weights[0].at(c, r) = 1.0f - t;
      splat.weights[1].at(c, r) = t;
      splat.weights[2].at(c, r) = r % 2 ? 0.3f : 0.0f;
    }
  set.layers[1] = splat_layer(std::move(splat));
  return set;
}

TEST(Terrain3DExport, ControlBitsDecodeToTheDominantMaterialsAndTheirBlend) {
  test::TempDir dir;
  const LayerSet set = mixed_set(40, 30);
  EngineExportOptions options;
  options.engine = Engine::terrain3d;
  run_export(set, options, dir.path());
  int w = 0, h = 0;
  const std::vector<float> control = read_exr(dir / "control.exr", w, h);
  ASSERT_EQ(w, 40);  // the world's cells as they are
  ASSERT_EQ(h, 30);
  const auto& bands = set.layers[1].bands;
  int blended = 0, single = 0;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const std::uint32_t bits = std::bit_cast<std::uint32_t>(control[std::size_t(r) * w + c]);
      const int base = int(bits >> 27 & 0x1F), overlay = int(bits >> 22 & 0x1F);
      const int blend = int(bits >> 14 & 0xFF);
      EXPECT_EQ(bits & 0x3FFFu, 0u) << "uv angle, uv scale, hole, navigation, autoshader: 0";
      // The two heaviest, lowest index first on ties.
      std::vector<int> order = {0, 1, 2};
      std::stable_sort(order.begin(), order.end(),
                       [&](int a, int b) { return bands[a].at(c, r) > bands[b].at(c, r); });
      const double w1 = bands[order[0]].at(c, r), w2 = bands[order[1]].at(c, r);
      ASSERT_EQ(base, order[0]) << c << " " << r;
      if (w2 > 0.0) {
        ASSERT_EQ(overlay, order[1]) << c << " " << r;
        ASSERT_EQ(blend, int(std::lround(255.0 * w2 / (w1 + w2)))) << c << " " << r;
        ++blended;
      } else {
        ASSERT_EQ(overlay, base);
        ASSERT_EQ(blend, 0);
        ++single;
      }
    }
  EXPECT_GT(blended, 100);
  EXPECT_GT(single, 10);  // column 0 of even rows: base alone

  const std::vector<float> heights = read_exr(dir / "height.exr", w, h);
  for (int r = 0; r < 30; r += 7)
    for (int c = 0; c < 40; c += 9)
      EXPECT_EQ(heights[std::size_t(r) * 40 + c], set.layers[0].bands[0].at(c, r));
  const nlohmann::json t3d = read_json(dir / "terrain3d.json");
  EXPECT_EQ(t3d["region_size"], 256);  // Terrain3D's default holds 40 x 30 in one region
  EXPECT_EQ(t3d["import_position"][0], 0);
  EXPECT_EQ(t3d["vertex_spacing"].get<double>(), 10.0);
  EXPECT_EQ(t3d["textures"][2]["material"], "bank");
  const std::string script = test::read_file(dir / "import_terrain3d.gd");
  EXPECT_NE(script.find("const REGION_SIZE := 256"), std::string::npos);
  EXPECT_NE(script.find("const VERTEX_SPACING := 10.0\n"), std::string::npos);  // a float
  EXPECT_NE(script.find("import_images(images, position, 0.0, 1.0)"), std::string::npos);
}

TEST(Terrain3DExport, RegionSizeGrowsWithTheWorldAndTheImportIsCentredOnRegions) {
  test::TempDir dir;
  EngineExportOptions options;
  options.engine = Engine::terrain3d;
  // 9000 cells: 32 regions of 256 hold 8192, so 512 (18 regions, the first at -9).
  LayerSet set;
  set.grid = GridSpec{9000, 3, 0.0, 30.0, 10.0, 10.0};
  set.crs_wkt = test::utm31n_wkt();
  set.layers.push_back(height_layer(Raster<float>(9000, 3, 5.0f)));
  run_export(set, options, dir.path());
  const nlohmann::json t3d = read_json(dir / "terrain3d.json");
  EXPECT_EQ(t3d["region_size"], 512);
  EXPECT_EQ(t3d["regions"][0], 18);
  EXPECT_EQ(t3d["import_position"][0], -9 * 512);
  EXPECT_EQ(t3d["import_position"][1], 0);
  options.size = 513;
  EXPECT_THROW(run_export(set, options, dir / "sized"), Error);
}

// X spacing == Y spacing for every engine on a 200 x 150 world: the longer side fills the
// heightmap, the shorter is padded (edge heights carried on), the plane read back in place.
TEST(SquarePixels, EveryEngineKeepsOneSpacingAndPadsTheShorterSide) {
  const LayerSet set = test::interop_set(200, 150);  // heights 100 + col + row / 3, 10 m cells
  const auto plane = [](double east_m, double south_m) {
    return 100.0 + east_m / 10.0 + south_m / 10.0 / 3.0;
  };
  {
    test::TempDir dir;
    run_export(set, {}, dir.path());
    const nlohmann::json ue = read_json(dir / "unreal.json");
    const double sx = ue["scale"][0], sy = ue["scale"][1];
    EXPECT_NEAR(sx, sy, 1e-9);
    EXPECT_NEAR(sx, 199.0 * 1000.0 / 252.0, 1e-9);  // 200 cells -> 253 vertices
    const Image map = read_image(dir / "heightmap.png");
    ASSERT_EQ(map.width, 253);
    ASSERT_EQ(map.height, 253);  // 189 rows of world: 253, padded
    const int world_rows = ue["padding"]["world_window"][3];
    EXPECT_EQ(world_rows, int(std::floor(149.0 * 1000.0 / sx)) + 1);
    const double min = ue["height_min_m"], step = ue["height_step_m"];
    for (int r = 0; r < 253; r += 12)
      for (int c = 0; c < 253; c += 21) {
        const double expected = plane(c * sx / 100.0, std::min(r, world_rows - 1) * sx / 100.0);
        EXPECT_NEAR(min + map.at(c, r) * step, expected, step + 1e-3) << c << " " << r;
      }
    const Image visibility = read_image(dir / "visibility.png");
    EXPECT_EQ(visibility.at(5, world_rows - 1), 0.0);
    EXPECT_EQ(visibility.at(5, world_rows), 255.0);
  }
  {
    test::TempDir dir;
    EngineExportOptions options;
    options.engine = Engine::unity;
    run_export(set, options, dir.path());
    const nlohmann::json unity = read_json(dir / "unity.json");
    EXPECT_NEAR(unity["terrain_size"][0].get<double>(), unity["terrain_size"][2].get<double>(),
                1e-9);
    EXPECT_NEAR(unity["terrain_size"][0].get<double>(), 1990.0, 1e-9);  // 256 cells -> 257
    // Row 0 of the file is the south edge: the world's southern cell centres.
    const std::string raw = test::read_file(dir / "heightmap.raw");
    ASSERT_EQ(raw.size(), 257u * 257u * 2u);
    const double s = 1990.0 / 256.0, min = unity["height_min_m"], max = unity["height_max_m"];
    const auto height_at = [&](int c, int file_row) {
      const std::size_t i = (std::size_t(file_row) * 257 + c) * 2;
      const int v = int(std::uint8_t(raw[i])) | int(std::uint8_t(raw[i + 1])) << 8;
      return min + v * (max - min) / 65535.0;
    };
    const double step = (max - min) / 65535.0;
    const int world_rows = unity["padding"]["world_window"][3];
    for (int file_row = 0; file_row < 257; file_row += 16) {
      // metres north of the southern centres, clamped to the world
      const double north_m = std::min(file_row, world_rows - 1) * s;
      EXPECT_NEAR(height_at(64, file_row), plane(64 * s, 1490.0 - north_m), step + 1e-3)
          << file_row;
    }
  }
  {
    test::TempDir dir;
    EngineExportOptions options;
    options.engine = Engine::godot;
    run_export(set, options, dir.path());
    const nlohmann::json godot = read_json(dir / "godot.json");
    EXPECT_NEAR(godot["map_scale"][0].get<double>(), godot["map_scale"][2].get<double>(), 1e-9);
    int w = 0, h = 0;
    const std::vector<float> heights = read_exr(dir / "height.exr", w, h);
    ASSERT_EQ(w, 257);
    ASSERT_EQ(h, 257);
    const double s = godot["map_scale"][0];
    const int world_rows = godot["padding"]["world_window"][3];
    EXPECT_EQ(world_rows, int(std::floor(1490.0 / s)) + 1);
    for (int r = 0; r < 257; r += 32)
      EXPECT_NEAR(heights[std::size_t(r) * 257 + 100],
                  plane(100 * s, std::min(r, world_rows - 1) * s), 1e-3)
          << r;
    EXPECT_EQ(read_image(dir / "mask.png").at(0, world_rows), 0.0);
  }
  {
    test::TempDir dir;
    EngineExportOptions options;
    options.engine = Engine::terrain3d;
    run_export(set, options, dir.path());
    const nlohmann::json t3d = read_json(dir / "terrain3d.json");
    EXPECT_EQ(t3d["size"][0], 200);
    EXPECT_EQ(t3d["size"][1], 150);
    EXPECT_EQ(t3d["vertex_spacing"].get<double>(), 10.0);  // one spacing: Terrain3D's only
  }
}

TEST(UnrealSize, AnySizeUnrealImportsIsTakenWithAWarningWhenNotRecommended) {
  test::TempDir dir;
  EngineExportOptions options;
  options.size = 1000;
  const auto result = run_export(test::interop_set(200, 150), options, dir.path());
  const Image map = read_image(dir / "heightmap.png");
  EXPECT_EQ(map.width, 1000);
  EXPECT_EQ(map.height, 1000);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_NE(result.warnings[0].find("1000 is not one of Epic's recommended sizes"),
            std::string::npos);
  const nlohmann::json ue = read_json(dir / "unreal.json");
  EXPECT_NEAR(ue["scale"][0].get<double>(), ue["scale"][1].get<double>(), 1e-9);
  options.size = 2017;
  EXPECT_TRUE(
      run_export(test::interop_set(200, 150), options, dir / "recommended").warnings.empty());
  options.size = 5;
  OutputTransaction tx;
  try {
    export_for_engine(test::interop_set(), {}, options, dir / "small", tx);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("size 5 is not one the engine takes: 8 ... 8129"),
              std::string::npos)
        << e.what();
  }
}

// The heights before the run: the result minus a known bump, so the delta is the bump.
Raster<float> input_of(const LayerSet& set) {
  Raster<float> input = set.layers[0].bands[0];
  for (int r = 0; r < input.height; ++r)
    for (int c = 0; c < input.width; ++c)
      input.at(c, r) -= float(std::sin(c * 0.3) * 2.0 + (r % 5 == 0 ? 1.5 : 0.0));
  input.at(3, 4) = std::nanf("");  // nodata before: no delta
  return input;
}

TEST(EditLayers, HeightDeltaIsResultMinusInputAndWeightLayersSumToTheSplat) {
  const LayerSet set = mixed_set(127, 127);  // Unreal's 127: the cells are the vertices
  const Raster<float> input = input_of(set);
  const Raster<float>& output = set.layers[0].bands[0];
  for (const Engine engine : {Engine::unreal, Engine::terrain3d, Engine::godot}) {
    SCOPED_TRACE(to_string(engine));
    test::TempDir dir;
    EngineExportOptions options;
    options.engine = engine;
    options.layers = true;
    if (engine == Engine::godot) options.size = 129;
    run_export(set, options, dir.path(), &input);
    int w = 0, h = 0;
    const std::vector<float> delta = read_exr(dir / "layers/height_delta.exr", w, h);
    if (engine != Engine::godot) {
      ASSERT_EQ(w, 127);
      for (int r = 0; r < 127; r += 5)
        for (int c = 0; c < 127; c += 7) {
          const float expected = (c == 3 && r == 4) ? 0.0f : output.at(c, r) - input.at(c, r);
          ASSERT_EQ(delta[std::size_t(r) * 127 + c], expected) << c << " " << r;
        }
      EXPECT_EQ(delta[4 * 127 + 3], 0.0f);
    } else {
      ASSERT_EQ(w, 129);  // resampled onto 129 vertices: bilinear between the cells' deltas
      EXPECT_NEAR(delta[0], output.at(0, 0) - input.at(0, 0), 1e-4);
      EXPECT_NEAR(delta[129 * 129 - 1], output.at(126, 126) - input.at(126, 126), 1e-4);
    }
    if (engine == Engine::unreal) {
      // The edit layer's 16 bits: 32768 + delta / step, the heightmap's Z step.
      const double step = read_json(dir / "unreal.json")["height_step_m"];
      const Image png = read_image(dir / "layers/height_delta.png");
      for (int r = 0; r < 127; r += 11)
        for (int c = 0; c < 127; c += 13)
          EXPECT_EQ(png.at(c, r), 32768.0 + std::lround(delta[std::size_t(r) * 127 + c] / step));
    }
    // Weight layers: every material but base; with base's weight they sum to 255.
    EXPECT_FALSE(fs::exists(dir / "layers/weight_base.png"));
    const Image road = read_image(dir / "layers/weight_road.png");
    const Image bank = read_image(dir / "layers/weight_bank.png");
    ASSERT_EQ(road.width, w);
    const auto json = read_json(dir / (to_string(engine) + ".json"));
    ASSERT_EQ(json["layers"]["weights"].size(), 2u);
    std::vector<double> total(road.pixels.size(), 0.0);
    for (std::size_t p = 0; p < total.size(); ++p) total[p] = road.pixels[p] + bank.pixels[p];
    if (engine == Engine::unreal) {
      const Image base = read_image(dir / "weightmap_base.png");
      const Image baked_road = read_image(dir / "weightmap_road.png");
      for (std::size_t p = 0; p < total.size(); ++p) {
        ASSERT_EQ(total[p] + base.pixels[p], 255.0) << p;
        ASSERT_EQ(road.pixels[p], baked_road.pixels[p]) << p;
      }
    } else {
      // Against the splat itself: the layers' sum is 255 x (road + bank) within the rounding.
      for (int r = 0; r < 127; r += 9)
        for (int c = 0; c < 127; c += 10) {
          if (engine == Engine::godot) continue;
          const auto& b = set.layers[1].bands;
          const double splat = 255.0 * (b[1].at(c, r) + b[2].at(c, r)) /
                               (b[0].at(c, r) + b[1].at(c, r) + b[2].at(c, r));
          EXPECT_NEAR(total[std::size_t(r) * 127 + c], splat, 1.0) << c << " " << r;
        }
    }
  }
  // Layers without the heights before the run: one clear error.
  test::TempDir dir;
  EngineExportOptions options;
  options.layers = true;
  EXPECT_THROW(run_export(set, options, dir.path()), Error);
}

// Tiles keep one spacing too: a non-square world in Unreal tiles of 127 is the single 253 x 253
// heightmap (the same spacing, the shorter side padded) cut into windows sharing their edges;
// Unity's tiles of 129 are the single 257 x 257 heightmap's windows likewise.
TEST(SquarePixels, TilesOfANonSquareWorldAreWindowsOfTheSquareHeightmap) {
  test::TempDir dir;
  const LayerSet set = test::interop_set(200, 150);
  write_geotiff(set, set.layers[0], dir / "height.tif");
  write_geotiff(set, set.layers[1], dir / "splat.tif");
  run_export(set, {}, dir / "whole");
  EngineExportOptions options;
  options.tile_size = 127;
  OutputTransaction tx;
  export_tiles_for_engine({dir / "height.tif", dir / "splat.tif", set.crs_wkt}, {}, options,
                          dir / "tiles", tx);
  tx.commit();
  const nlohmann::json tiles = read_json(dir / "tiles/unreal.json");
  const nlohmann::json whole = read_json(dir / "whole/unreal.json");
  EXPECT_NEAR(tiles["scale"][0].get<double>(), tiles["scale"][1].get<double>(), 1e-9);
  EXPECT_NEAR(tiles["scale"][0].get<double>(), whole["scale"][0].get<double>(), 1e-9);
  ASSERT_EQ(tiles["tiles_x"], 2);
  ASSERT_EQ(tiles["tiles_y"], 2);
  EXPECT_EQ(tiles["padding"]["world_window"], whole["padding"]["world_window"]);
  const Image map = read_image(dir / "whole/heightmap.png");
  const Image road = read_image(dir / "whole/weightmap_road.png");
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const std::string suffix = "_x" + std::to_string(i) + "_y" + std::to_string(j) + ".png";
      const Image tile = read_image(dir / "tiles" / ("heightmap" + suffix));
      const Image tile_road = read_image(dir / "tiles" / ("weightmap_road" + suffix));
      ASSERT_EQ(tile.width, 127);
      for (int r = 0; r < 127; ++r)
        for (int c = 0; c < 127; ++c) {
          ASSERT_EQ(tile.at(c, r), map.at(i * 126 + c, j * 126 + r)) << i << j << " " << c << r;
          ASSERT_EQ(tile_road.at(c, r), road.at(i * 126 + c, j * 126 + r));
        }
    }

  // Unity: padded north (the corner stays south-west); tiles of 129 are windows of the 257.
  EngineExportOptions unity;
  unity.engine = Engine::unity;
  run_export(set, unity, dir / "unity_whole");
  unity.tile_size = 129;
  OutputTransaction unity_tx;
  export_tiles_for_engine({dir / "height.tif", dir / "splat.tif", set.crs_wkt}, {}, unity,
                          dir / "unity_tiles", unity_tx);
  unity_tx.commit();
  const nlohmann::json unity_tiles = read_json(dir / "unity_tiles/unity.json");
  EXPECT_NEAR(unity_tiles["terrain_size"][0].get<double>(),
              unity_tiles["terrain_size"][2].get<double>(), 1e-9);
  const std::string whole_raw = test::read_file(dir / "unity_whole/heightmap.raw");
  ASSERT_EQ(whole_raw.size(), 257u * 257u * 2u);
  for (int z = 0; z < 2; ++z)
    for (int x = 0; x < 2; ++x) {
      const std::string tile =
          test::read_file(dir / "unity_tiles" /
                          ("heightmap_" + std::to_string(x) + "_" + std::to_string(z) + ".raw"));
      ASSERT_EQ(tile.size(), 129u * 129u * 2u);
      for (int rr = 0; rr < 129; ++rr)  // file rows: south to north in both
        ASSERT_EQ(tile.substr(std::size_t(rr) * 129 * 2, 129 * 2),
                  whole_raw.substr((std::size_t(z * 128 + rr) * 257 + x * 128) * 2, 129 * 2))
            << x << " " << z << " " << rr;
    }
}

}  // namespace
}  // namespace tw
