// The demo pipeline end to end through the library: georeferenced layers, splat weights that
// sum to 1, heights changed along rivers and roads and nowhere beyond the features' reach,
// and the same bytes for any thread count.
#include "pipeline/run.hpp"

#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>
#include <GeographicLib/UTMUPS.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "geo/features.hpp"
#include "geo/geodesic.hpp"
#include "geo/heightfield.hpp"
#include "layers/write.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/stage_options.hpp"
#include "pipeline/detail/stages.hpp"
#include "raster/distance.hpp"
#include "raster/foldover.hpp"
#include "raster/rasterize.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

constexpr double kResolution = 15.0;  // metres: 480 x 480 cells, a fast run

// The demo's terrain path without its synthesis (patterns_test.cpp covers synthesis on a
// small world; the demo's DP takes about a minute on 2 cores).
PipelineConfig demo_config(const fs::path& out) {
  PipelineConfig config =
      load_pipeline(test::source_dir() / "pipelines/demo.yaml",
                    {{"resolution", std::to_string(kResolution)}, {"output.dir", out.string()}});
  for (FeatureClassConfig& c : config.features) drop_method_options(c.methods, kPatternsMethodName);
  drop_method_options(config.methods, kPatternsMethodName);  // its synthesis_order
  return config;
}

// One run of the demo shared by the tests of this suite.
class DemoRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    out_ = new test::TempDir;
    config_ = new PipelineConfig(demo_config(out_->path()));
    report_ = new RunReport(run_pipeline(*config_));
    HeightfieldOptions options;
    options.resolution = kResolution;
    options.resampling = config_->resampling;  // the demo reads its DEM as the run does
    original_ = new Heightfield(read_heightfield(config_->heightfield->string(), options));
  }
  static void TearDownTestSuite() {
    delete original_;
    delete report_;
    delete config_;
    delete out_;
  }

  static fs::path out(const std::string& name) { return out_->path() / name; }

  // The lines of the class `name`, read as the run read them.
  static std::vector<LineFeature> lines_of(const std::string& name) {
    for (const FeatureClassConfig& c : config_->features) {
      if (c.name != name) continue;
      Warnings warnings;
      return detail::load_feature_class(c, *original_, warnings);
    }
    ADD_FAILURE() << "no class " << name;
    return {};
  }

  static test::TempDir* out_;
  static PipelineConfig* config_;
  static RunReport* report_;
  static Heightfield* original_;
};

test::TempDir* DemoRun::out_ = nullptr;
PipelineConfig* DemoRun::config_ = nullptr;
RunReport* DemoRun::report_ = nullptr;
Heightfield* DemoRun::original_ = nullptr;

TEST_F(DemoRun, WritesEveryLayerAndAReport) {
  for (const char* name : {"height.exr", "height.tif", "splat.exr", "splat.tif", "avoidance.exr",
                           "avoidance.tif", "preview.png", "features.geojson", "report.json"}) {
    EXPECT_TRUE(fs::exists(out(name))) << name;
  }
  EXPECT_EQ(report_->outputs.size(), 9u);
  std::vector<std::string> stages;
  for (const auto& s : report_->stages) stages.push_back(s.stage);
  // The whole run in stages (docs/cli.md); `untimed`, the remainder, last when there is one.
  if (!stages.empty() && stages.back() == "untimed") stages.pop_back();
  EXPECT_EQ(stages, (std::vector<std::string>{"setup", "ingest", "ribbons", "terrain", "plan",
                                              "inputs", "render", "layers", "preview",
                                              "features.geojson", "placements", "manifest"}));

  std::ifstream in(out("report.json"));
  const nlohmann::json json = nlohmann::json::parse(in);
  EXPECT_EQ(json["seed"], 7);
  ASSERT_EQ(json["classes"].size(), 3u);
  EXPECT_EQ(json["classes"][0]["name"], "ridges");
  EXPECT_EQ(json["classes"][2]["name"], "roads");
  EXPECT_EQ(json["classes"][2]["features"].size(), 5u);  // samples/README.md: 5 roads
  for (const auto& f : json["classes"][2]["features"]) {
    EXPECT_GT(f["length_m"].get<double>(), 100.0);
    EXPECT_EQ(f["pieces"].get<int>(), int(std::ceil(f["length_m"].get<double>() / 4.0)));
  }
  EXPECT_GT(json["forbidden_pixels"].get<std::int64_t>(), 0);
}

TEST_F(DemoRun, LayersAreGeoreferencedLikeTheHeightfield) {
  const GridSpec& grid = original_->grid;
  EXPECT_EQ(report_->grid, grid);
  OGRSpatialReference expected;
  ASSERT_EQ(expected.importFromWkt(original_->crs_wkt.c_str()), OGRERR_NONE);
  for (const char* name : {"height.tif", "splat.tif", "avoidance.tif"}) {
    SCOPED_TRACE(name);
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(out(name).c_str(), GDAL_OF_RASTER));
    ASSERT_NE(ds, nullptr);
    EXPECT_EQ(ds->GetRasterXSize(), grid.width);
    EXPECT_EQ(ds->GetRasterYSize(), grid.height);
    double gt[6];
    ASSERT_EQ(ds->GetGeoTransform(gt), CE_None);
    const auto want = grid.geotransform();
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(gt[i], want[i], 1e-6) << i;
    ASSERT_NE(ds->GetSpatialRef(), nullptr);
    EXPECT_TRUE(ds->GetSpatialRef()->IsSame(&expected));
  }
  const ExrContents exr = read_exr(out("height.exr"));
  EXPECT_EQ(exr.crs_wkt, original_->crs_wkt);
  EXPECT_DOUBLE_EQ(exr.origin.x, grid.origin_x);
  EXPECT_DOUBLE_EQ(exr.origin.y, grid.origin_y);
  EXPECT_DOUBLE_EQ(exr.pixel_size.x, grid.pixel_width);
}

TEST_F(DemoRun, SplatWeightsSumToOneAndShowTheFeatures) {
  const ExrContents splat = read_exr(out("splat.exr"));
  ASSERT_FALSE(splat.bands.empty());
  double worst = 0.0;
  for (std::size_t i = 0; i < splat.bands[0].pixels.size(); ++i) {
    double sum = 0.0;
    for (const auto& band : splat.bands) sum += band.pixels[i];
    worst = std::max(worst, std::abs(sum - 1.0));
  }
  // The EXR holds the weights as half floats: each within 2^-11 of itself (relative), so
  // their sum within 2^-11 of the float32 sum (which is 1 within 1e-6).
  EXPECT_LT(worst, std::ldexp(1.0, -11) + 1e-5);
  for (const char* material : {"splat.road", "splat.riverbed", "splat.ridge_rock"}) {
    const auto it = std::find(splat.channels.begin(), splat.channels.end(), material);
    ASSERT_NE(it, splat.channels.end()) << material;
    const auto& band = splat.bands[it - splat.channels.begin()];
    // Roads are narrower than the 15 m pixels: partial coverage.
    EXPECT_GT(*std::max_element(band.pixels.begin(), band.pixels.end()), 0.5f) << material;
  }
}

// Heights of the run's output and of the input at points along `lines` (every pixel).
struct Samples {
  std::vector<float> before, after;
};
Samples sample_along(const std::vector<LineFeature>& lines, const Heightfield& original,
                     const Raster<float>& after) {
  Samples s;
  for (const LineFeature& line : lines) {
    for (std::size_t i = 0; i + 1 < line.points.size(); ++i) {
      const double length = distance(line.points[i], line.points[i + 1]);
      for (double t = 0.0; t < length; t += original.grid.pixel_width) {
        const Vec2 p =
            original.grid.world_to_pixel(lerp(line.points[i], line.points[i + 1], t / length));
        const int col = int(p.x), row = int(p.y);
        if (!after.inside(col, row)) continue;
        s.before.push_back(original.height.at(col, row));
        s.after.push_back(after.at(col, row));
      }
    }
  }
  return s;
}

TEST_F(DemoRun, RiversAreCarvedAndRoadsGraded) {
  const ExrContents height = read_exr(out("height.exr"));
  ASSERT_EQ(height.bands.size(), 1u);
  const Samples rivers = sample_along(lines_of("rivers"), *original_, height.bands[0]);
  ASSERT_GT(rivers.before.size(), 100u);
  std::size_t carved = 0;
  for (std::size_t i = 0; i < rivers.before.size(); ++i)
    carved += rivers.after[i] < rivers.before[i] - 1.0f;
  EXPECT_GT(double(carved) / rivers.before.size(), 0.9) << carved << " of " << rivers.before.size();

  const Samples roads = sample_along(lines_of("roads"), *original_, height.bands[0]);
  ASSERT_GT(roads.before.size(), 100u);
  std::size_t graded = 0;
  for (std::size_t i = 0; i < roads.before.size(); ++i)
    graded += std::abs(roads.after[i] - roads.before[i]) > 0.05f;
  EXPECT_GT(double(graded) / roads.before.size(), 0.5) << graded << " of " << roads.before.size();
}

TEST_F(DemoRun, NothingChangesBeyondTheFeaturesReach) {
  std::vector<std::vector<LineFeature>> lines;
  for (const FeatureClassConfig& c : config_->features) lines.push_back(lines_of(c.name));
  const std::vector<TerrainFeature> features =
      detail::terrain_features(detail::terrain_options(*config_), lines);
  std::vector<std::vector<Vec2>> centerlines;
  std::vector<double> widths;
  const double margin = 2.0 * original_->grid.pixel_width;
  for (const TerrainFeature& f : features) {
    centerlines.push_back(f.centerline.points);
    if (f.centerline.closed) centerlines.back().push_back(f.centerline.points.front());
    widths.push_back(2.0 * (feature_reach(f) + margin));
  }
  Raster<std::uint8_t> near;
  burn_buffered_lines(centerlines, widths, original_->grid, Window::whole(original_->grid), near,
                      1);
  const ExrContents height = read_exr(out("height.exr"));
  std::size_t far = 0, changed = 0;
  for (std::size_t i = 0; i < near.pixels.size(); ++i) {
    if (near.pixels[i]) continue;
    ++far;
    changed += height.bands[0].pixels[i] != original_->height.pixels[i];
  }
  EXPECT_GT(far, near.pixels.size() / 4);
  EXPECT_EQ(changed, 0u) << "of " << far << " pixels beyond reach";
}

// The run's avoidance layer against a naive whole-grid build: every ribbon's footprint and
// fold-overs burnt on the whole grid, and the distance field capped at avoidance.max_distance.
TEST_F(DemoRun, AvoidanceLayerEqualsTheWholeGridMapCapped) {
  std::vector<std::vector<LineFeature>> lines;
  for (const FeatureClassConfig& c : config_->features) lines.push_back(lines_of(c.name));
  Warnings warnings;
  const detail::FeatureRibbons ribbons = detail::make_feature_ribbons(
      detail::ribbon_options(*config_), lines, original_->grid, warnings);
  const detail::ExistingFeatures existing =
      detail::load_existing(config_->existing, *original_, config_->repair, warnings);
  const GridSpec& grid = original_->grid;
  const Window whole = Window::whole(grid);
  Raster<std::uint8_t> forbidden(grid.width, grid.height, 0);
  burn_polygons(existing.polygons, grid, whole, forbidden, 1);
  burn_polygons(ribbons.junction_discs, grid, whole, forbidden, 1);
  burn_buffered_lines(existing.lines, existing.line_widths, grid, whole, forbidden, 1);
  for (const auto& class_ribbons : ribbons.ribbons)
    for (const Ribbon& r : class_ribbons) {
      burn_polygons(piece_polygons(r), grid, whole, forbidden, 1);
      const Raster<std::uint8_t> folds = foldover_mask(r, grid, whole);
      for (std::size_t i = 0; i < folds.pixels.size(); ++i) forbidden.pixels[i] |= folds.pixels[i];
    }
  Raster<float> distance = distance_to_mask(forbidden, grid.pixel_width, grid.pixel_height);
  const float cap = float(config_->avoidance.max_distance);
  for (float& d : distance.pixels) d = std::min(d, cap);

  const ExrContents exr = read_exr(out("avoidance.exr"));
  ASSERT_EQ(exr.channels, (std::vector<std::string>{"forbidden", "distance"}));
  std::vector<std::uint8_t> written;
  for (const float v : exr.bands[0].pixels) written.push_back(v > 0.0f ? 1 : 0);
  EXPECT_EQ(written, forbidden.pixels);
  EXPECT_EQ(exr.bands[1].pixels, distance.pixels);
  EXPECT_GT(std::count(distance.pixels.begin(), distance.pixels.end(), cap), 0);  // it capped
  EXPECT_EQ(std::count(forbidden.pixels.begin(), forbidden.pixels.end(), 1),
            report_->forbidden_pixels);
}

TEST(PipelineRun, SameBytesForAnyThreadCount) {
  test::TempDir one, two;
  PipelineConfig config = demo_config(one.path());
  config.resolution = 40.0;
  RunOptions options;
  options.threads = 1;
  run_pipeline(config, options);
  options.threads = 2;
  options.output_dir = two.path();
  run_pipeline(config, options);
  for (const char* name : {"height.exr", "splat.exr", "avoidance.exr"}) {
    const ExrContents a = read_exr(one / name), b = read_exr(two / name);
    ASSERT_EQ(a.bands.size(), b.bands.size()) << name;
    for (std::size_t i = 0; i < a.bands.size(); ++i) {
      EXPECT_EQ(std::memcmp(a.bands[i].pixels.data(), b.bands[i].pixels.data(),
                            a.bands[i].pixels.size() * sizeof(float)),
                0)
          << name << " " << a.channels[i];
    }
  }
}

TEST(PipelineRun, AFailingRunWritesNothing) {
  test::TempDir out;
  PipelineConfig config = demo_config(out.path());
  config.features.back().source = out / "missing.gpkg";
  EXPECT_THROW(run_pipeline(config), Error);
  EXPECT_TRUE(fs::is_empty(out.path()));
}

TEST(PipelineRun, ValidateOnlyReadsAndWritesNothing) {
  test::TempDir out;
  RunOptions options;
  options.write_outputs = false;
  const RunReport report = run_pipeline(demo_config(out / "never"), options);
  EXPECT_FALSE(fs::exists(out / "never"));
  EXPECT_EQ(report.classes.size(), 3u);
  EXPECT_TRUE(report.outputs.empty());
}

// `output.crs: local` (docs/pipeline.md, issue #24): the local transverse Mercator centred on
// the DEM, for a geographic DEM as the docs promise (it was refused as an unknown CRS).
TEST(PipelineRun, OutputCrsLocalIsATransverseMercatorOnTheDemsCentre) {
  test::TempDir out;
  const PipelineConfig config = load_pipeline(
      test::source_dir() / "pipelines/luxembourg.yaml",
      {{"output.dir", out.path().string()}, {"output.crs", "local"}, {"resolution", "500"}});
  EXPECT_EQ(config.output.crs, "local");
  const RunReport report = run_pipeline(config);
  OGRSpatialReference srs;
  ASSERT_EQ(srs.importFromWkt(report.crs_wkt.c_str()), OGRERR_NONE);
  EXPECT_TRUE(srs.IsProjected());
  EXPECT_STREQ(srs.GetAttrValue("PROJECTION"), "Transverse_Mercator");
  EXPECT_NEAR(srs.GetProjParm(SRS_PP_CENTRAL_MERIDIAN), 6.3208333, 1e-4);
  EXPECT_NEAR(srs.GetProjParm(SRS_PP_LATITUDE_OF_ORIGIN), 49.5708333, 1e-4);
  EXPECT_EQ(report.classes.size(), 2u);
}

// The geographic sample (EPSG:4326 DEM and lines): warped into the UTM zone of its centre,
// lengths in metres that agree with GeographicLib's geodesics, nodata kept outside the country.
TEST(PipelineRun, GeographicSamplePipelineWorksInMetres) {
  test::TempDir out;
  const PipelineConfig config = load_pipeline(test::source_dir() / "pipelines/luxembourg.yaml",
                                              {{"output.dir", out.path().string()}});
  const RunReport report = run_pipeline(config);
  // The DEM's centre, 6.3208 E 49.5708 N, lies in zone floor((6.3208 + 180) / 6) + 1 = 32,
  // north of the equator: EPSG:32632, named so in report.json.
  OGRSpatialReference srs;
  ASSERT_EQ(srs.importFromWkt(report.crs_wkt.c_str()), OGRERR_NONE);
  ASSERT_NE(srs.GetAuthorityCode(nullptr), nullptr);
  EXPECT_STREQ(srs.GetAuthorityCode(nullptr), "32632");
  const auto json = nlohmann::json::parse(std::ifstream(out / "report.json"));
  EXPECT_EQ(json["grid"]["crs"], "EPSG:32632");
  EXPECT_DOUBLE_EQ(report.grid.pixel_width, 50.0);
  // The grid is the bounding box of the DEM in that zone: its corners (6.116667..6.525 E,
  // 49.441667..49.70 N) projected by GeographicLib's own UTM (not PROJ, which warped the DEM)
  // lie within it, and it reaches at most 2 pixels past them (a parallel bows ~21 m over the
  // DEM's 30 km; the grid rounds out to whole pixels).
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const double lon : {6.1166667, 6.525})
    for (const double lat : {49.4416667, 49.7}) {
      int zone = 0;
      bool north = false;
      double x = 0, y = 0;
      GeographicLib::UTMUPS::Forward(lat, lon, zone, north, x, y, 32);
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  const GridSpec& g = report.grid;
  const double gx1 = g.origin_x + g.width * g.pixel_width;
  const double gy0 = g.origin_y - g.height * g.pixel_height;
  EXPECT_LE(g.origin_x, x0 + 1.0);
  EXPECT_GE(g.origin_x, x0 - 100.0);
  EXPECT_GE(gx1, x1 - 1.0);
  EXPECT_LE(gx1, x1 + 100.0);
  EXPECT_GE(g.origin_y, y1 - 1.0);
  EXPECT_LE(g.origin_y, y1 + 100.0);
  EXPECT_LE(gy0, y0 + 1.0);
  EXPECT_GE(gy0, y0 - 100.0);
  ASSERT_EQ(report.classes.size(), 2u);
  const FeatureClassReport& roads = report.classes[1];
  ASSERT_EQ(roads.name, "roads");
  ASSERT_EQ(roads.features.size(), 1u);
  const double geodesic =
      geodesic_length({{6.17, 49.5}, {6.22, 49.55}, {6.27, 49.59}, {6.31, 49.64}});
  EXPECT_NEAR(roads.features[0].length_m / geodesic, 1.0, 2e-3)
      << roads.features[0].length_m << " m against " << geodesic << " m";
  EXPECT_DOUBLE_EQ(roads.features[0].width_m, 7.0);
  const ExrContents height = read_exr(out / "height.exr");
  std::size_t nodata = 0;
  for (float h : height.bands[0].pixels) nodata += std::isnan(h);
  EXPECT_GT(nodata, height.bands[0].pixels.size() / 5);  // outside Luxembourg
  EXPECT_LT(nodata, height.bands[0].pixels.size() * 3 / 4);
}

}  // namespace
}  // namespace tw
