// Engine exports read back (issue #12, item 1): sizes, bit depths, value ranges, layer sums,
// heights within one 16-bit step, nodata filled, the numbers to type in, the splines.
#include "layers/export.hpp"

#include <OpenImageIO/imageio.h>
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "sample_layers.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

struct Image {
  int width = 0, height = 0;
  GDALDataType type = GDT_Unknown;
  std::vector<std::vector<double>> bands;
};

Image read_image(const fs::path& path) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
  if (!ds) throw std::runtime_error("cannot open " + path.string());
  Image img{
      ds->GetRasterXSize(), ds->GetRasterYSize(), ds->GetRasterBand(1)->GetRasterDataType(), {}};
  for (int b = 1; b <= ds->GetRasterCount(); ++b) {
    auto& v = img.bands.emplace_back(std::size_t(img.width) * img.height);
    if (ds->GetRasterBand(b)->RasterIO(GF_Read, 0, 0, img.width, img.height, v.data(), img.width,
                                       img.height, GDT_Float64, 0, 0) != CE_None)
      throw std::runtime_error("cannot read " + path.string());
  }
  return img;
}

nlohmann::json read_json(const fs::path& path) {
  return nlohmann::json::parse(std::ifstream(path));
}

// The plane of interop_set at a world point.
double plane(const GridSpec& g, double x, double y) {
  const Vec2 p = g.world_to_pixel({x, y});
  return 100.0 + (p.x - 0.5) + (p.y - 0.5) / 3.0;
}

EngineExportResult run_export(const LayerSet& set, EngineExportOptions options, const fs::path& dir,
                              const std::vector<ExportCurve>& curves = {}) {
  OutputTransaction tx;
  EngineExportResult result = export_for_engine(set, curves, options, dir, tx);
  tx.commit();
  return result;
}

TEST(EngineExport, UnrealHeightmapSpansTheFull16BitsAndRoundTripsWithinOneStep) {
  test::TempDir dir;
  const LayerSet set = test::interop_set(127, 127);
  const std::vector<ExportCurve> curves = {
      {"roads", "road", 7, 6.0, {{500105.0, 5001165.0}, {500605.0, 5000665.0}}}};
  const auto result = run_export(set, {}, dir.path(), curves);
  const Image map = read_image(dir / "heightmap.png");
  ASSERT_EQ(map.width, 127);  // 127 cells: Epic's smallest size, no resampling
  ASSERT_EQ(map.height, 127);
  EXPECT_EQ(map.type, GDT_UInt16);
  ASSERT_EQ(map.bands.size(), 1u);
  const auto [lo, hi] = std::minmax_element(map.bands[0].begin(), map.bands[0].end());
  EXPECT_EQ(*lo, 0.0);
  EXPECT_EQ(*hi, 65535.0);
  const nlohmann::json ue = read_json(dir / "unreal.json");
  const double min = ue["height_min_m"], max = ue["height_max_m"];
  EXPECT_FLOAT_EQ(min, 100.0f);
  EXPECT_FLOAT_EQ(max, 100.0f + 126.0f + 126.0f / 3.0f);
  const double step = (max - min) / 65535.0;
  double worst = 0.0;
  for (std::size_t i = 0; i < map.bands[0].size(); ++i)
    worst =
        std::max(worst, std::abs(min + map.bands[0][i] * step - set.layers[0].bands[0].pixels[i]));
  EXPECT_LE(worst, step);
  // What Unreal makes of a value v (Epic's formula: Location.Z + (v - 32768) * Scale.Z / 128
  // cm) is the true height within the rounding, half a step: 0 at min, 65535 at max.
  const double scale_z = ue["scale"][2], location_z = ue["location_cm"][2];
  const auto unreal_m = [&](double v) {
    return (location_z + (v - 32768.0) * scale_z / 128.0) / 100;
  };
  EXPECT_NEAR(unreal_m(0), min, 1e-9);
  EXPECT_NEAR(unreal_m(65535), max, 1e-9);
  double worst_unreal = 0.0;
  for (std::size_t i = 0; i < map.bands[0].size(); ++i)
    worst_unreal = std::max(worst_unreal,
                            std::abs(unreal_m(map.bands[0][i]) - set.layers[0].bands[0].pixels[i]));
  EXPECT_LE(worst_unreal, step / 2 + 1e-6);
  EXPECT_NEAR(ue["scale"][0].get<double>(), 1000.0, 1e-9);  // 10 m cells, in centimetres
  ASSERT_EQ(result.settings.size(), 4u);
  EXPECT_NE(result.settings[2].find(fmt::format("Z {:.4f}", scale_z)), std::string::npos)
      << result.settings[2];

  // One 8-bit weightmap per material, summing to 255 everywhere.
  const auto names = ue["weightmaps"];
  ASSERT_EQ(names.size(), 6u);
  std::vector<Image> weights;
  for (const auto& w : names) weights.push_back(read_image(dir / w["file"].get<std::string>()));
  EXPECT_EQ(names[1]["material"], "road");
  for (const Image& w : weights) {
    EXPECT_EQ(w.type, GDT_Byte);
    EXPECT_EQ(w.width, 127);
  }
  for (std::size_t p = 0; p < weights[0].bands[0].size(); ++p) {
    double sum = 0.0;
    for (const Image& w : weights) sum += w.bands[0][p];
    ASSERT_EQ(sum, 255.0) << p;
  }
  EXPECT_EQ(weights[1].bands[0][7 * 127 + 13], 255.0);  // column 13 % 6 == 1: road

  // The spline's points in centimetres from the landscape corner (the north-west cell centre).
  const nlohmann::json splines = read_json(dir / "splines.json");
  ASSERT_EQ(splines["splines"].size(), 1u);
  const auto& point = splines["splines"][0]["points"][1];
  EXPECT_NEAR(point["engine"][0].get<double>(), (500605.0 - 500005.0) * 100.0, 1e-6);
  EXPECT_NEAR(point["engine"][1].get<double>(), (5001265.0 - 5000665.0) * 100.0, 1e-6);
  EXPECT_NEAR(point["world"][2].get<double>(), plane(set.grid, 500605.0, 5000665.0), 1e-3);
  EXPECT_NEAR(point["engine"][2].get<double>(), point["world"][2].get<double>() * 100.0, 1e-6);
  EXPECT_EQ(splines["splines"][0]["width"].get<double>(), 600.0);
  EXPECT_EQ(test::lines_of(test::read_file(dir / "splines.csv")).size(), 3u);  // header + 2
}

TEST(EngineExport, UnrealResamplesOntoVerticesAtTheOuterCellCentres) {
  test::TempDir dir;
  const LayerSet set = test::interop_set(200, 200);
  run_export(set, {}, dir.path());
  const Image map = read_image(dir / "heightmap.png");
  ASSERT_EQ(map.width, 253);  // the nearest size >= 200
  ASSERT_EQ(map.height, 253);
  const nlohmann::json ue = read_json(dir / "unreal.json");
  const double min = ue["height_min_m"], max = ue["height_max_m"];
  EXPECT_NEAR(min, 100.0, 1e-4);  // the corner vertices are the corner cells' centres
  EXPECT_NEAR(max, 100.0 + 199.0 + 199.0 / 3.0, 1e-3);
  const double step = (max - min) / 65535.0;
  for (int r = 0; r < 253; r += 21)
    for (int c = 0; c < 253; c += 19) {
      const double expected = 100.0 + c * 199.0 / 252.0 + r * 199.0 / 252.0 / 3.0;
      EXPECT_NEAR(min + map.bands[0][std::size_t(r) * 253 + c] * step, expected, step + 1e-4)
          << c << " " << r;
    }
  EXPECT_NEAR(ue["scale"][0].get<double>(), 199.0 * 1000.0 / 252.0, 1e-9);
  EXPECT_NEAR(ue["scale"][1].get<double>(), 199.0 * 1000.0 / 252.0, 1e-9);
  // (Non-square worlds: tests/layers/export_engines_test.cpp, SquarePixels.)
}

TEST(EngineExport, NodataIsFilledFromTheNearestHeightsOrAGivenValue) {
  test::TempDir dir;
  LayerSet set = test::interop_set(127, 127);
  for (int r = 0; r < 10; ++r)
    for (int c = 0; c < 10; ++c) set.layers[0].bands[0].at(c, r) = std::nanf("");
  run_export(set, {}, dir / "nearest");
  // Filled from the valid cells around the hole: never below the lowest of them (row 0,
  // column 10: 110 m; column 0, row 10: 103.33 m), so no hole is the landscape's lowest point.
  const nlohmann::json nearest = read_json(dir / "nearest/unreal.json");
  EXPECT_GE(nearest["height_min_m"].get<double>(), 103.33);
  EXPECT_LT(nearest["height_min_m"].get<double>(), 110.0);
  EngineExportOptions given;
  given.nodata_height = 50.0;
  run_export(set, given, dir / "given");
  const Image map = read_image(dir / "given/heightmap.png");
  EXPECT_EQ(read_json(dir / "given/unreal.json")["height_min_m"].get<double>(), 50.0);
  EXPECT_EQ(map.bands[0][5 * 127 + 5], 0.0);  // the hole at the given height
  EXPECT_GT(map.bands[0][50 * 127 + 50], 0.0);
}

TEST(EngineExport, UnityWritesLittleEndianRawBottomUpAndRgbaControlMaps) {
  test::TempDir dir;
  const LayerSet set = test::interop_set(40, 30);
  EngineExportOptions options;
  options.engine = Engine::unity;
  run_export(set, options, dir.path());
  const nlohmann::json unity = read_json(dir / "unity.json");
  ASSERT_EQ(unity["heightmap_resolution"], 65);  // 2^6 + 1 >= 40
  ASSERT_EQ(fs::file_size(dir / "heightmap.raw"), 65u * 65u * 2u);
  const std::string raw = test::read_file(dir / "heightmap.raw");
  const auto sample = [&](int c, int r) {
    const std::size_t i = (std::size_t(r) * 65 + c) * 2;
    return int(std::uint8_t(raw[i])) | int(std::uint8_t(raw[i + 1])) << 8;
  };
  EXPECT_EQ(sample(0, 64), 0);      // file row 64: padding north, the lowest corner (north-west)
  EXPECT_EQ(sample(64, 0), 65535);  // file row 0 = south edge: the highest corner (south-east)
  const double min = unity["height_min_m"], max = unity["height_max_m"];
  const double step = (max - min) / 65535.0;
  // Square: 390 m over 64 spacings on x and z alike; file row 16 is 16 spacings north of the
  // southern cell centres (the world's 290 m fill 48 rows, the rest is padding).
  const double s = 390.0 / 64.0;
  const double expected = 100.0 + 32 * s / 10.0 + (290.0 - 16 * s) / 10.0 / 3.0;
  EXPECT_NEAR(min + sample(32, 16) * step, expected, step + 1e-4);
  EXPECT_NEAR(unity["terrain_size"][0].get<double>(), 390.0, 1e-9);
  EXPECT_NEAR(unity["terrain_size"][1].get<double>(), max - min, 1e-9);
  EXPECT_NEAR(unity["terrain_size"][2].get<double>(), 390.0, 1e-9);
  EXPECT_EQ(unity["padding"]["world_window"][3], 48);
  EXPECT_EQ(sample(10, 60), sample(10, 47));  // padding: the northern edge carried on
  ASSERT_EQ(unity["layers"].size(), 6u);
  EXPECT_EQ(unity["layers"][5]["control"], "splatmap_1.png");
  EXPECT_EQ(unity["layers"][5]["channel"], "G");
  const Image first = read_image(dir / "splatmap_0.png");
  const Image second = read_image(dir / "splatmap_1.png");
  ASSERT_EQ(first.width, 64);
  ASSERT_EQ(first.bands.size(), 4u);
  EXPECT_EQ(first.type, GDT_Byte);
  for (std::size_t p = 0; p < first.bands[0].size(); ++p) {
    double sum = 0.0;
    for (const Image* img : {&first, &second})
      for (const auto& band : img->bands) sum += band[p];
    ASSERT_EQ(sum, 255.0) << p;
    ASSERT_EQ(second.bands[2][p] + second.bands[3][p], 0.0);  // no materials 7 and 8
  }
}

TEST(EngineExport, GodotHeightIsFloatMetresOrR16AndSplatSumsTo255) {
  test::TempDir dir;
  const LayerSet set = test::interop_set(40, 30);
  EngineExportOptions options;
  options.engine = Engine::godot;
  run_export(set, options, dir / "exr");
  auto in = OIIO::ImageInput::open((dir / "exr/height.exr").string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec spec = in->spec();
  ASSERT_EQ(spec.width, 65);
  ASSERT_EQ(spec.nchannels, 1);
  EXPECT_EQ(spec.channelnames[0], "R");
  EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
  std::vector<float> h(65 * 65);
  ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, h.data()));
  EXPECT_NEAR(h[0], 100.0f, 1e-4f);
  const double s = 390.0 / 64.0;  // square: one spacing on x and z
  EXPECT_NEAR(h[16 * 65 + 32], 100.0 + 32 * s / 10.0 + 16 * s / 10.0 / 3.0, 1e-3);
  const Image splat = read_image(dir / "exr/splat_0.png");
  const Image splat1 = read_image(dir / "exr/splat_1.png");
  ASSERT_EQ(splat.width, 65);
  for (std::size_t p = 0; p < splat.bands[0].size(); ++p) {
    double sum = 0.0;
    for (const Image* img : {&splat, &splat1})
      for (const auto& band : img->bands) sum += band[p];
    ASSERT_EQ(sum, 255.0) << p;
  }
  options.godot_height = GodotHeightFormat::r16;
  options.size = 129;
  run_export(set, options, dir / "r16");
  EXPECT_EQ(fs::file_size(dir / "r16/height.r16"), 129u * 129u * 2u);
  EXPECT_EQ(read_json(dir / "r16/godot.json")["resolution"], 129);
}

TEST(EngineExport, ASizeTheEngineDoesNotTakeIsOneClearError) {
  test::TempDir dir;
  EngineExportOptions options;
  options.engine = Engine::unity;
  options.size = 1000;
  OutputTransaction tx;
  try {
    export_for_engine(test::interop_set(), {}, options, dir.path(), tx);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "export unity: size 1000 is not one the engine takes: 33 ... 4097 (2^n + 1)");
  }
  EXPECT_EQ(engine_heightmap_size(Engine::unreal, 1009), 1009);
  EXPECT_EQ(engine_heightmap_size(Engine::unreal, 1010), 2017);
  EXPECT_EQ(engine_heightmap_size(Engine::unity, 1000), 1025);
  EXPECT_EQ(parse_engine("godot"), Engine::godot);
  EXPECT_THROW(parse_engine("cryengine"), Error);
}

// A line beyond the map (features are read with a margin) is clipped to the terrain's extent
// in the engine, the corner cell centres; one that leaves and comes back is two splines. Every
// height is the terrain's there, never 0.
TEST(EngineExport, SplinesAreClippedToTheTerrainAndCarryItsHeights) {
  const LayerSet set = test::interop_set(40, 30);  // x 500000..500400, y 5000000..5000300
  const double west = 500005.0, east = 500395.0, south = 5000005.0, north = 5000295.0;
  // From 100 m west of the map, out through the north edge and back, to 50 m east of it.
  const std::vector<ExportCurve> curves = {{"rivers",
                                            "river",
                                            4,
                                            10.0,
                                            {{499900.0, 5000150.0},
                                             {500100.0, 5000150.0},
                                             {500200.0, 5000400.0},
                                             {500300.0, 5000150.0},
                                             {500450.0, 5000100.0}}}};
  for (const Engine engine : {Engine::unreal, Engine::unity, Engine::godot}) {
    SCOPED_TRACE(to_string(engine));
    test::TempDir dir;
    EngineExportOptions options;
    options.engine = engine;
    run_export(set, options, dir.path(), curves);
    const nlohmann::json splines = read_json(dir / "splines.json");
    ASSERT_EQ(splines["splines"].size(), 2u);
    EXPECT_EQ(splines["splines"][0]["name"], "rivers_4_0");
    EXPECT_EQ(splines["splines"][1]["name"], "rivers_4_1");
    int points = 0;
    for (const auto& spline : splines["splines"])
      for (const auto& p : spline["points"]) {
        const double x = p["world"][0], y = p["world"][1], z = p["world"][2];
        EXPECT_GE(x, west);
        EXPECT_LE(x, east);
        EXPECT_GE(y, south);
        EXPECT_LE(y, north);
        EXPECT_NEAR(z, plane(set.grid, x, y), 1e-3) << x << " " << y;
        EXPECT_GT(z, 100.0);
        ++points;
      }
    // The first part: the west edge, the inner vertex, the north edge; the second: the
    // north edge, the inner vertex, the east edge.
    EXPECT_EQ(points, 6);
    const auto& first = splines["splines"][0]["points"];
    EXPECT_EQ(first[0]["world"][0].get<double>(), west);
    EXPECT_EQ(first[0]["world"][1].get<double>(), 5000150.0);
    EXPECT_EQ(first[2]["world"][1].get<double>(), north);
    EXPECT_EQ(splines["splines"][1]["points"][2]["world"][0].get<double>(), east);
    EXPECT_EQ(test::lines_of(test::read_file(dir / "splines.csv")).size(), 7u);  // header + 6
  }
}

TEST(EngineExport, CenterlinesRoundTripThroughGeoJson) {
  test::TempDir dir;
  const std::vector<ExportCurve> curves = {
      {"roads", "road", 3, 6.5, {{500000.5, 5000000.25}, {500100.0, 5000200.0}}},
      {"rivers", "river", 9, 12.0, {{500001.0, 5000001.0}, {500002.0, 5000004.0}, {5e5, 5e6}}}};
  write_curves_geojson(curves, test::utm31n_wkt(), dir / "features.geojson");
  const auto back = read_curves_geojson(dir / "features.geojson");
  ASSERT_EQ(back.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back[i].feature_class, curves[i].feature_class);
    EXPECT_EQ(back[i].kind, curves[i].kind);
    EXPECT_EQ(back[i].fid, curves[i].fid);
    EXPECT_EQ(back[i].width, curves[i].width);
    ASSERT_EQ(back[i].points.size(), curves[i].points.size());
    for (std::size_t k = 0; k < back[i].points.size(); ++k) {
      EXPECT_NEAR(back[i].points[k].x, curves[i].points[k].x, 1e-3);
      EXPECT_NEAR(back[i].points[k].y, curves[i].points[k].y, 1e-3);
    }
  }
}

}  // namespace
}  // namespace tw
