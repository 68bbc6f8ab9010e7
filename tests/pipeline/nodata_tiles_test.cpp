// Tiles equal the untiled run on any DEM (docs/tiles.md, docs/pipeline.md "Nodata in every
// layer"): a seeded property test over random DEMs with random nodata holes and margins (nodata
// NaN, -32768, -9999, 0 or none; projected and geographic, so warped), random tilings, roads
// with a pattern, a conformed river, an existing lake, an area and a grown class, comparing
// bit for bit every band of every layer (the VRT mosaics, every tile's GeoTIFF and EXR) and
// the Unreal and Unity exports; then the real DEMs: samples/dem_wgs84.tif (Int16, nodata
// -32768 over 45 %) and samples/dem.tif warped with -dstnodata -32768.
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <sstream>

#include "layers/write.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/run.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

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
  for (int b = 0; b < ds->GetRasterCount(); ++b)
    EXPECT_EQ(
        ds->GetRasterBand(b + 1)->RasterIO(
            GF_Read, 0, 0, w, h, pixels.data() + std::size_t(w) * h * b, w, h, GDT_Float32, 0, 0),
        CE_None);
  return pixels;
}

// Pixels whose bits differ (NaN equals the same NaN, -0 differs from +0); a size mismatch
// counts every pixel.
std::int64_t differing(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) return std::int64_t(std::max(a.size(), b.size()));
  std::int64_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(float)) != 0;
  return n;
}

std::vector<float> crop(const std::vector<float>& whole, int width, int height, std::size_t bands,
                        const Window& w) {
  std::vector<float> out;
  for (std::size_t b = 0; b < bands; ++b)
    for (int row = w.row0; row < w.row_end(); ++row) {
      const float* from = whole.data() + (b * height + row) * std::size_t(width) + w.col0;
      out.insert(out.end(), from, from + w.width);
    }
  return out;
}

// Differing pixels per layer ("height", "splat", "avoidance") and per export file, tiled
// against untiled: the mosaic, every tile's GeoTIFF and EXR against the untiled window (so
// overlaps too), and every file the exports wrote (images pixel by pixel, others byte by byte).
std::map<std::string, std::int64_t> tiled_vs_untiled(const fs::path& untiled, const fs::path& tiled,
                                                     const std::vector<TileSpec>& tiles) {
  std::map<std::string, std::int64_t> diff;
  for (const std::string layer : {"height", "splat", "avoidance"}) {
    int width = 0, height = 0;
    const std::vector<float> whole = gdal_pixels(untiled / (layer + ".tif"), &width, &height);
    const std::size_t bands = whole.size() / (std::size_t(width) * height);
    diff[layer + " mosaic"] = differing(gdal_pixels(tiled / (layer + ".vrt")), whole);
    const ExrContents whole_exr = read_exr(untiled / (layer + ".exr"));
    std::int64_t tif = 0, exr = 0;
    for (const TileSpec& t : tiles) {
      const fs::path stem = tiled / "tiles" / tile_file_stem(layer, t);
      tif += differing(gdal_pixels(stem.string() + ".tif"),
                       crop(whole, width, height, bands, t.halo_window));
      const ExrContents part = read_exr(stem.string() + ".exr");
      EXPECT_EQ(part.channels, whole_exr.channels);
      for (std::size_t c = 0; c < part.bands.size() && c < whole_exr.bands.size(); ++c)
        exr += differing(part.bands[c].pixels,
                         crop(whole_exr.bands[c].pixels, width, height, 1, t.halo_window));
    }
    diff[layer + " tiles tif"] = tif;
    diff[layer + " tiles exr"] = exr;
  }
  for (const char* engine : {"unreal", "unity"}) {
    const fs::path a = untiled / "export" / engine, b = tiled / "export" / engine;
    if (!fs::exists(a)) continue;
    for (const auto& entry : fs::directory_iterator(a)) {
      const fs::path name = entry.path().filename();
      const std::string key = std::string(engine) + "/" + name.string();
      if (!fs::exists(b / name)) {
        diff[key] = -1;
        continue;
      }
      if (name.extension() == ".png")
        diff[key] = differing(gdal_pixels(a / name), gdal_pixels(b / name));
      else
        diff[key] = test::read_file(a / name) != test::read_file(b / name);
    }
  }
  return diff;
}

std::string describe(const std::map<std::string, std::int64_t>& diff) {
  std::ostringstream s;
  for (const auto& [key, n] : diff)
    if (n != 0) s << "  " << key << ": " << n << " differ\n";
  return s.str();
}

void expect_all_equal(const std::map<std::string, std::int64_t>& diff) {
  std::int64_t total = 0;
  for (const auto& [key, n] : diff) total += n != 0;
  EXPECT_EQ(total, 0) << describe(diff);
}

// Every splat and avoidance band is NaN exactly where the height is nodata, in the EXR (what
// the renderer produced) and the GeoTIFF of the untiled run; returns the nodata pixel count.
std::int64_t expect_nodata_in_every_layer(const fs::path& untiled) {
  const ExrContents height = read_exr(untiled / "height.exr");
  std::int64_t nodata = 0;
  for (const float h : height.bands[0].pixels) nodata += std::isnan(h);
  for (const std::string layer : {"splat", "avoidance"}) {
    const ExrContents exr = read_exr(untiled / (layer + ".exr"));
    const std::vector<float> tif = gdal_pixels(untiled / (layer + ".tif"));
    const std::size_t n = height.bands[0].pixels.size();
    for (std::size_t b = 0; b < exr.bands.size(); ++b) {
      std::int64_t wrong = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const bool hole = std::isnan(height.bands[0].pixels[i]);
        wrong += std::isnan(exr.bands[b].pixels[i]) != hole;
        wrong += std::isnan(tif[b * n + i]) != hole;
      }
      EXPECT_EQ(wrong, 0) << layer << " " << exr.channels[b];
    }
  }
  return nodata;
}

// ---- the random worlds ----

struct Case {
  std::uint32_t seed = 0;
  bool geographic = false;
  std::optional<double> nodata;  // none: a DEM without nodata (no holes)
};

// A GeoTIFF of `w` x `h` smooth heights (100..260 m) with random nodata discs and a ragged
// margin along one or two edges, in EPSG:32631 (10 m cells) or EPSG:4326 (1e-4 degrees).
struct RandomDem {
  int width = 0, height = 0;
  double gt[6] = {};
  std::string crs;
  Vec2 world(double col, double row) const {  // pixel -> the DEM's CRS
    return {gt[0] + col * gt[1], gt[3] + row * gt[5]};
  }
};

RandomDem write_random_dem(const fs::path& path, const Case& c, std::mt19937& rng) {
  RandomDem dem;
  dem.width = 70 + int(rng() % 50);
  dem.height = 60 + int(rng() % 50);
  if (c.geographic) {
    dem.crs = "EPSG:4326";
    const double gt[6] = {3.0 + (rng() % 100) * 1e-3,  1.2e-4, 0,
                          45.0 + (rng() % 100) * 1e-3, 0,      -1e-4};
    std::copy(gt, gt + 6, dem.gt);
  } else {
    dem.crs = "EPSG:32631";
    const double gt[6] = {500000.0, 10.0, 0, 5001300.0, 0, -10.0};
    std::copy(gt, gt + 6, dem.gt);
  }
  const double phase = (rng() % 628) / 100.0;
  std::vector<float> cells(std::size_t(dem.width) * dem.height);
  for (int y = 0; y < dem.height; ++y)
    for (int x = 0; x < dem.width; ++x)
      cells[std::size_t(y) * dem.width + x] =
          float(100.0 + 80.0 * x / dem.width +
                40.0 * std::sin(0.13 * x + phase) * std::cos(0.11 * y - phase) + 0.3 * y);
  if (c.nodata) {
    const float nodata = float(*c.nodata);
    const int discs = 1 + int(rng() % 4);
    for (int d = 0; d < discs; ++d) {
      const int cx = int(rng() % dem.width), cy = int(rng() % dem.height);
      const int r = 3 + int(rng() % 10);
      for (int y = std::max(0, cy - r); y < std::min(dem.height, cy + r + 1); ++y)
        for (int x = std::max(0, cx - r); x < std::min(dem.width, cx + r + 1); ++x)
          if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r)
            cells[std::size_t(y) * dem.width + x] = nodata;
    }
    // A ragged margin along the west or east edge, and maybe the north one.
    const bool west = rng() % 2;
    int depth = 2 + int(rng() % 8);
    for (int y = 0; y < dem.height; ++y) {
      depth = std::clamp(depth + int(rng() % 3) - 1, 0, dem.width / 4);
      for (int k = 0; k < depth; ++k)
        cells[std::size_t(y) * dem.width + (west ? k : dem.width - 1 - k)] = nodata;
    }
    if (rng() % 2)
      for (int x = 0; x < dem.width; ++x)
        for (int k = 0; k < int(rng() % 6); ++k) cells[std::size_t(k) * dem.width + x] = nodata;
  }
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GetGDALDriverManager()->GetDriverByName("GTiff")->Create(
      path.c_str(), dem.width, dem.height, 1, GDT_Float32, nullptr));
  EXPECT_NE(ds, nullptr);
  ds->SetGeoTransform(dem.gt);
  OGRSpatialReference srs;
  srs.SetFromUserInput(dem.crs.c_str());
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  ds->SetSpatialRef(&srs);
  if (c.nodata) ds->GetRasterBand(1)->SetNoDataValue(*c.nodata);
  EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, dem.width, dem.height, cells.data(),
                                           dem.width, dem.height, GDT_Float32, 0, 0),
            CE_None);
  return dem;
}

// WKT of a polyline through `n` random points, the first and last beyond the DEM's edges (so
// lines run off the map as real features do), in the DEM's CRS.
std::string random_line(const RandomDem& dem, std::mt19937& rng, int n) {
  std::ostringstream wkt;
  wkt.precision(12);
  wkt << "LINESTRING (";
  for (int i = 0; i < n; ++i) {
    const double t = double(i) / (n - 1);
    const bool end = i == 0 || i == n - 1;
    const double col = end ? (i == 0 ? -0.15 : 1.15) * dem.width
                           : (0.1 + 0.8 * t) * dem.width + double(rng() % 21) - 10.0;
    const double row = (0.1 + 0.8 * (rng() % 1000) / 1000.0) * dem.height;
    const Vec2 p = dem.world(col, row);
    wkt << (i ? ", " : "") << p.x << ' ' << p.y;
  }
  wkt << ")";
  return wkt.str();
}

std::string box_polygon(const RandomDem& dem, double c0, double r0, double c1, double r1) {
  const Vec2 a = dem.world(c0 * dem.width, r0 * dem.height);
  const Vec2 b = dem.world(c1 * dem.width, r1 * dem.height);
  std::ostringstream wkt;
  wkt.precision(12);
  wkt << "POLYGON ((" << a.x << ' ' << a.y << ", " << b.x << ' ' << a.y << ", " << b.x << ' ' << b.y
      << ", " << a.x << ' ' << b.y << ", " << a.x << ' ' << a.y << "))";
  return wkt.str();
}

constexpr const char* kPipeline = R"(version: 1
seed: 4
heightfield: dem.tif
output: { dir: out, preview: false }
synthesis_resolution: 2
avoidance: { max_distance: 60 }
export: { unreal: { tile_size: 0 }, unity: { tile_size: 0 } }
existing:
  - { source: map.gpkg, layer: lakes }
precedence: [rivers, roads, hedges]
features:
  rivers:
    source: map.gpkg
    layer: rivers
    kind: river
    width: 12
    profile: { depth: 2, bank_width: 6, falloff: 20 }
    conform: { corridor: 60 }
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
  hedges:
    kind: hedge
    grow: { element: hedge.json, region: { source: map.gpkg, layer: hedges }, max_ornaments: 3 }
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

class NodataTiles : public ::testing::TestWithParam<Case> {};

TEST_P(NodataTiles, EveryLayerAndExportEqualsTheUntiledRunBitForBit) {
  const Case c = GetParam();
  std::mt19937 rng(c.seed);
  test::TempDir dir;
  const RandomDem dem = write_random_dem(dir / "dem.tif", c, rng);
  test::write_layer(dir / "map.gpkg", "roads",
                    {{random_line(dem, rng, 5)}, {random_line(dem, rng, 4)}}, dem.crs);
  test::write_layer(dir / "map.gpkg", "rivers", {{random_line(dem, rng, 6)}}, dem.crs);
  test::write_layer(dir / "map.gpkg", "lakes", {{box_polygon(dem, 0.45, 0.1, 0.55, 0.2)}}, dem.crs);
  test::write_layer(dir / "map.gpkg", "fields", {{box_polygon(dem, 0.2, 0.55, 0.5, 0.85)}},
                    dem.crs);
  test::write_layer(dir / "map.gpkg", "hedges", {{box_polygon(dem, 0.6, 0.5, 0.95, 0.9)}}, dem.crs);
  fs::copy_file(test::source_dir() / "samples/sketches/vineyard.geojson", dir / "vineyard.geojson");
  for (const char* name : {"hedge.json", "hedge.png"})
    fs::copy_file(test::source_dir() / "samples/ornaments" / name, dir / name);
  const fs::path exemplars = test::source_dir() / "samples/exemplars";
  test::crop_raster(exemplars / "cobble_edging_200x56.png", dir / "cobble.png", "PNG", 60, 56);
  test::crop_raster(exemplars / "cobble_edging_200x56_height.tif", dir / "cobble_height.tif",
                    "GTiff", 60, 56);

  const int size = 17 + int(rng() % 40), overlap = int(rng() % 6);
  SCOPED_TRACE(::testing::Message() << "seed " << c.seed << ", " << dem.width << " x " << dem.height
                                    << (c.geographic ? " geographic" : " projected") << ", tiles "
                                    << size << " overlap " << overlap);
  const auto config = [&](const std::string& out, std::vector<Override> overrides) {
    overrides.push_back({"output.dir", (dir / out).string()});
    if (c.geographic) overrides.push_back({"resolution", "10"});
    return parse_pipeline(kPipeline, "p.yaml", dir.path(), overrides);
  };
  const RunReport untiled = run_pipeline(config("untiled", {}));
  const std::string tiling =
      "{ size: " + std::to_string(size) + ", overlap: " + std::to_string(overlap) + " }";
  const RunReport tiled = run_pipeline(config("tiled", {{"output.tiles", tiling}}));
  const std::vector<TileSpec> tiles = tile_grid(untiled.grid, size, overlap);
  ASSERT_EQ(tiled.tiles.tiles.size(), tiles.size());
  ASSERT_GT(tiles.size(), 3u);

  const std::int64_t nodata = expect_nodata_in_every_layer(dir / "untiled");
  if (c.nodata || c.geographic) {
    EXPECT_GT(nodata, 0);  // the case has holes to get wrong (a warp leaves margins)
  } else {
    EXPECT_EQ(nodata, 0);
  }
  const auto diff = tiled_vs_untiled(dir / "untiled", dir / "tiled", tiles);
  std::int64_t files = 0;
  for (const auto& [key, n] : diff) files += key.find('/') != std::string::npos;
  EXPECT_GE(files, 10);  // heightmaps, weightmaps, sidecars and splines of both engines
  expect_all_equal(diff);
  EXPECT_EQ(untiled.forbidden_pixels, tiled.forbidden_pixels);
  for (const char* file : {"areas.gpkg", "instances.csv", "ornaments.gpkg", "features.geojson"})
    EXPECT_EQ(test::read_file(dir / "untiled" / file), test::read_file(dir / "tiled" / file))
        << file;
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

INSTANTIATE_TEST_SUITE_P(RandomDems, NodataTiles,
                         ::testing::Values(Case{11, false, kNaN}, Case{12, false, -32768.0},
                                           Case{13, false, -9999.0}, Case{14, false, 0.0},
                                           Case{15, false, std::nullopt}, Case{16, true, -32768.0},
                                           Case{17, true, kNaN}, Case{18, true, std::nullopt}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           return "seed" + std::to_string(info.param.seed);
                         });

// The real DEMs: Luxembourg's Int16 DEM (nodata -32768 outside the country, 45 %) warped into
// UTM at 100 m with the Moselle and a road, and samples/dem.tif warped into EPSG:4326 with
// -dstnodata -32768 (a Float32 DEM whose nodata margins are a number) with samples/map.gpkg.
TEST(NodataTilesReal, LuxembourgInt16TilesEqualTheUntiledRun) {
  test::TempDir dir;
  const fs::path pipeline = test::source_dir() / "pipelines/luxembourg.yaml";
  const auto config = [&](const std::string& out, std::vector<Override> overrides) {
    overrides.push_back({"output.dir", (dir / out).string()});
    overrides.push_back({"resolution", "100"});
    overrides.push_back({"output.preview", "false"});
    overrides.push_back({"export", "{ unreal: { tile_size: 0 }, unity: { tile_size: 0 } }"});
    return load_pipeline(pipeline, overrides);
  };
  const RunReport untiled = run_pipeline(config("untiled", {}));
  run_pipeline(config("tiled", {{"output.tiles", "{ size: 61, overlap: 2 }"}}));
  const std::int64_t nodata = expect_nodata_in_every_layer(dir / "untiled");
  EXPECT_GT(nodata, untiled.grid.cell_count() / 3);
  expect_all_equal(
      tiled_vs_untiled(dir / "untiled", dir / "tiled", tile_grid(untiled.grid, 61, 2)));
}

TEST(NodataTilesReal, OlindaWarpedWithANumericNodataTilesEqualTheUntiledRun) {
  test::TempDir dir;
  {
    GDALAllRegister();
    const char* args[] = {"-t_srs",  "EPSG:4326", "-dstnodata", "-32768", "-ot",
                          "Float32", "-r",        "bilinear",   nullptr};
    GDALWarpAppOptions* options = GDALWarpAppOptionsNew(const_cast<char**>(args), nullptr);
    GDALDatasetH source = GDALOpen((test::source_dir() / "samples/dem.tif").c_str(), GA_ReadOnly);
    ASSERT_NE(source, nullptr);
    int error = 0;
    GDALDatasetH warped = GDALWarp((dir / "dem.tif").c_str(), nullptr, 1, &source, options, &error);
    GDALWarpAppOptionsFree(options);
    ASSERT_NE(warped, nullptr);
    ASSERT_EQ(error, 0);
    GDALClose(warped);
    GDALClose(source);
  }
  fs::copy_file(test::source_dir() / "samples/map.gpkg", dir / "map.gpkg");
  constexpr const char* kOlinda = R"(version: 1
seed: 2
heightfield: dem.tif
resolution: 60
output: { dir: out, preview: false }
export: { unreal: { tile_size: 0 }, unity: { tile_size: 0 } }
existing:
  - { source: map.gpkg, layer: existing }
features:
  rivers: { source: map.gpkg, layer: rivers, kind: river, width_attribute: width, width: 8 }
  roads: { source: map.gpkg, layer: roads, kind: road, width_attribute: width, width: 6 }
)";
  const auto config = [&](const std::string& out, std::vector<Override> overrides) {
    overrides.push_back({"output.dir", (dir / out).string()});
    return parse_pipeline(kOlinda, "olinda.yaml", dir.path(), overrides);
  };
  const RunReport untiled = run_pipeline(config("untiled", {}));
  run_pipeline(config("tiled", {{"output.tiles", "{ size: 29, overlap: 3 }"}}));
  EXPECT_GT(expect_nodata_in_every_layer(dir / "untiled"), 100);
  expect_all_equal(
      tiled_vs_untiled(dir / "untiled", dir / "tiled", tile_grid(untiled.grid, 29, 3)));
}

}  // namespace
}  // namespace tw
