// Pattern synthesis inside the pipeline (issue #4) on a small world: a 640 m DEM, two roads
// crossing (a junction), a closed ring road, and a 60 x 56 crop of the cobble exemplar with its
// height channel, so that every run takes a second or two.
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "core/error.hpp"
#include "core/split_mix.hpp"
#include "core/warnings.hpp"
#include "layers/write.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/stage_options.hpp"
#include "pipeline/detail/stages.hpp"
#include "pipeline/methods/patterns/pattern_report.hpp"
#include "pipeline/methods/patterns/patterns.hpp"
#include "pipeline/run.hpp"
#include "raster/foldover.hpp"
#include "synth/placements_io.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr const char* kPipeline = R"(
version: 1
seed: 11
heightfield: dem.tif
resolution: 10
output: { dir: out }
synthesis_resolution: 1
features:
  roads:
    source: map.gpkg
    layer: roads
    kind: road
    width_attribute: width
    width: 6
    synthesis:
      exemplar: cobble.png
      width: 8
      scale: 5
      delta: 8
      channels: { alpha: splat.cobble, height: height }
)";

// The small world in a temporary folder.
class SmallWorld : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_dem(dir_ / "dem.tif");  // 64 x 64 cells of 10 m from (500000, 5000640)
    test::write_layer(dir_ / "map.gpkg", "roads",
                      {{"LINESTRING (500050 5000300, 500590 5000330)", 6.0},
                       {"LINESTRING (500310 5000050, 500330 5000590)", 6.0},
                       {ring(500320, 5000320, 150), 6.0}});
    const fs::path exemplars = test::source_dir() / "samples/exemplars";
    test::crop_raster(exemplars / "cobble_edging_200x56.png", dir_ / "cobble.png", "PNG", 60, 56);
    test::crop_raster(exemplars / "cobble_edging_200x56_height.tif", dir_ / "cobble_height.tif",
                      "GTiff", 60, 56);
  }

  static std::string ring(double cx, double cy, double r) {
    std::ostringstream wkt;
    wkt.precision(10);
    wkt << "LINESTRING (";
    for (int i = 0; i <= 48; ++i) {
      const double a = 2.0 * M_PI * (i % 48) / 48.0;
      wkt << (i ? ", " : "") << cx + r * std::cos(a) << ' ' << cy + r * std::sin(a);
    }
    wkt << ")";
    return wkt.str();
  }

  PipelineConfig config(std::vector<Override> overrides = {}) const {
    overrides.push_back({"output.dir", (dir_ / "out").string()});
    return parse_pipeline(kPipeline, "small.yaml", dir_.path(), overrides);
  }

  static std::string bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }

  static nlohmann::json report_of(const fs::path& out) {
    std::ifstream in(out / "report.json");
    return nlohmann::json::parse(in);
  }

  test::TempDir dir_;
};

TEST_F(SmallWorld, PatternsBecomeSplatAndHeightWithoutViolations) {
  const RunReport report = run_pipeline(config());
  const fs::path out = dir_ / "out";
  EXPECT_EQ(detail::pattern_violations(report), 0);
  const nlohmann::json json = report_of(out);
  ASSERT_EQ(json["classes"][0]["features"].size(), 3u);
  for (const auto& f : json["classes"][0]["features"]) {
    const auto& s = f["synthesis"];
    EXPECT_EQ(s["violations"], 0);
    EXPECT_GT(s["mean_valid_positions"].get<double>(), 10.0);
    EXPECT_GT(s["omega"].get<std::int64_t>(), 0);
    EXPECT_LE(s["mean_seam_cost_stitched"].get<double>(), s["mean_seam_cost"].get<double>());
    const Synthesis placements =
        load_placements((out / s["placements"].get<std::string>()).string());
    EXPECT_EQ(int(placements.placements.size()), f["pieces"].get<int>());
  }
  EXPECT_EQ(json["pattern_violations"], 0);
  // The ring road is closed and synthesized as a cycle.
  EXPECT_TRUE(load_placements((out / "placements/roads_3.json").string()).closed);

  const ExrContents splat = read_exr(out / "splat.exr");
  const auto cobble = std::find(splat.channels.begin(), splat.channels.end(), "splat.cobble");
  ASSERT_NE(cobble, splat.channels.end());
  const auto& pattern = splat.bands[cobble - splat.channels.begin()];
  double worst = 0.0;
  std::size_t covered = 0;
  for (std::size_t i = 0; i < pattern.pixels.size(); ++i) {
    double sum = 0.0;
    for (const auto& band : splat.bands) sum += band.pixels[i];
    worst = std::max(worst, std::abs(sum - 1.0));
    covered += pattern.pixels[i] > 0.0f;
  }
  // The EXR holds the weights as half floats: each within 2^-11 of itself (relative), so
  // their sum within 2^-11 of the float32 sum (which is 1 within 1e-6).
  EXPECT_LT(worst, std::ldexp(1.0, -11) + 1e-5);
  EXPECT_GT(covered, 100u);

  // Height detail: the same run without the height mapping differs only where the pattern
  // covers, and somewhere it does.
  const ExrContents with_detail = read_exr(out / "height.exr");
  run_pipeline(config({{"features.roads.synthesis.channels", "{alpha: splat.cobble}"}}));
  const ExrContents without = read_exr(out / "height.exr");
  std::size_t raised = 0, outside = 0;
  for (std::size_t i = 0; i < pattern.pixels.size(); ++i) {
    const float d = with_detail.bands[0].pixels[i] - without.bands[0].pixels[i];
    if (d != 0.0f) {
      ++raised;
      outside += pattern.pixels[i] == 0.0f;
      EXPECT_GT(d, 0.0f);
    }
  }
  EXPECT_GT(raised, 50u);
  EXPECT_EQ(outside, 0u);

  // A run with fewer features leaves none of the previous run's placements (issue #9 item 7).
  run_pipeline(config({{"features.roads.where", "fid = 3"}}));
  std::vector<std::string> placements;
  for (const auto& entry : fs::directory_iterator(out / "placements"))
    placements.push_back(entry.path().filename().string());
  EXPECT_EQ(placements, std::vector<std::string>{"roads_3.json"});
  EXPECT_EQ(report_of(out)["classes"][0]["features"].size(), 1u);
}

TEST_F(SmallWorld, SameBytesOnEveryBackendAndThreadCount) {
  const char* files[] = {"height.exr", "splat.exr", "placements/roads_1.json",
                         "placements/roads_2.json", "placements/roads_3.json"};
  std::vector<std::string> reference;
  int run = 0;
  for (const char* backend : {"cpu", "opencl"}) {
    for (const int threads : {1, 2}) {
      RunOptions options;
      options.backend = backend;
      options.threads = threads;
      options.output_dir = dir_ / ("run" + std::to_string(run++));
      run_pipeline(config(), options);
      const nlohmann::json json = report_of(*options.output_dir);
      EXPECT_THAT(json["classes"][0]["features"][0]["synthesis"]["backend"].get<std::string>(),
                  ::testing::StartsWith(backend));
      std::vector<std::string> contents;
      for (const char* f : files) contents.push_back(bytes(*options.output_dir / f));
      if (reference.empty()) {
        reference = contents;
        continue;
      }
      for (std::size_t i = 0; i < contents.size(); ++i) {
        EXPECT_TRUE(contents[i] == reference[i])
            << files[i] << " on " << backend << ", " << threads << " threads";
      }
    }
  }
}

TEST_F(SmallWorld, PlacementsDoNotDependOnTheOutputResolution) {
  RunOptions options;
  options.output_dir = dir_ / "fine";
  run_pipeline(config({{"resolution", "5"}}), options);
  options.output_dir = dir_ / "coarse";
  run_pipeline(config({{"resolution", "20"}}), options);
  for (const char* f : {"roads_1.json", "roads_2.json", "roads_3.json"}) {
    EXPECT_TRUE(bytes(dir_ / "fine/placements" / f) == bytes(dir_ / "coarse/placements" / f)) << f;
  }
  EXPECT_EQ(read_exr(dir_ / "fine/height.exr").bands[0].width, 128);
}

TEST_F(SmallWorld, SeedsGiveDifferentValidResults) {
  RunOptions options;
  options.output_dir = dir_ / "a";
  run_pipeline(config(), options);
  options.output_dir = dir_ / "b";
  const RunReport other = run_pipeline(config({{"seed", "12"}}), options);
  EXPECT_EQ(detail::pattern_violations(other), 0);
  EXPECT_FALSE(bytes(dir_ / "a/placements/roads_1.json") ==
               bytes(dir_ / "b/placements/roads_1.json"));
  EXPECT_NE(feature_seed(11, 11, 1), feature_seed(11, 11, 2));
  EXPECT_NE(feature_seed(11, 11, 1), feature_seed(12, 11, 1));
  EXPECT_EQ(feature_seed(11, 11, 1), feature_seed(11, 11, 1));
}

TEST_F(SmallWorld, AFeatureWithoutRoomFailsNamingItsFid) {
  // Only the first road (FID 1), under an existing polygon that covers all of it.
  test::write_layer(dir_ / "map.gpkg", "cover",
                    {{"POLYGON ((500000 5000260, 500640 5000260, 500640 5000370, 500000 5000370, "
                      "500000 5000260))"}});
  const std::vector<Override> overrides = {
      {"existing", "[{source: " + (dir_ / "map.gpkg").string() + ", layer: cover}]"},
      {"features.roads.where", "fid = 1"}};
  try {
    run_pipeline(config(overrides));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("features.roads: FID 1"));
    EXPECT_THAT(e.what(), HasSubstr("no room"));
  }
  auto strict = overrides;
  strict.push_back({"features.roads.synthesis.empty_pieces", "false"});
  try {
    run_pipeline(config(strict));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("FID 1"));
    EXPECT_THAT(e.what(), HasSubstr("piece 0"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "out/report.json"));
}

// The sparse canvas (16-cell tiles along each ribbon, most of the canvas absent) gives the dense
// canvas's results (one tile over the whole canvas) bit for bit, on roads with a junction, a
// closed ring that starts where it crosses another road, and a hairpin that folds over itself.
TEST_F(SmallWorld, SparseCanvasEqualsTheDenseCanvas) {
  test::write_layer(dir_ / "hairpin.gpkg", "roads",
                    {{"LINESTRING (500050 5000300, 500590 5000330)", 6.0},
                     {ring(500320, 5000320, 150), 6.0},
                     {"LINESTRING (500100 5000560, 500300 5000560, 500304 5000557, "
                      "500300 5000554, 500100 5000554)",
                      6.0}});
  const PipelineConfig c = config({{"features.roads.source", (dir_ / "hairpin.gpkg").string()},
                                   {"features.roads.synthesis.empty_pieces", "true"}});
  Warnings warnings;
  const Heightfield heightfield = detail::load_heightfield(detail::heightfield_input(c), warnings);
  const std::vector<std::vector<LineFeature>> lines = {
      detail::load_feature_class(c.features[0], heightfield, warnings)};
  const detail::ExistingFeatures existing =
      detail::load_existing(c.existing, heightfield, c.repair, warnings);
  const detail::FeatureRibbons ribbons =
      detail::make_feature_ribbons(detail::ribbon_options(c), lines, heightfield.grid, warnings);
  ASSERT_FALSE(ribbons.synthesis_junction_discs.empty());
  detail::PatternOptions dense_options;
  dense_options.backend = "cpu";
  dense_options.canvas_tile = 0;
  detail::PatternOptions sparse_options = dense_options;
  sparse_options.canvas_tile = 16;
  const detail::PatternRun dense =
      detail::synthesize_patterns(c, lines, ribbons, existing, dense_options);
  const detail::PatternRun sparse =
      detail::synthesize_patterns(c, lines, ribbons, existing, sparse_options);
  ASSERT_EQ(dense.patterns.size(), 3u);
  ASSERT_EQ(sparse.patterns.size(), 3u);
  std::int64_t folded = 0;
  for (std::size_t p = 0; p < 3; ++p) {
    const detail::FeaturePattern& a = sparse.patterns[p];
    const detail::FeaturePattern& b = dense.patterns[p];
    ASSERT_EQ(a.canvas, b.canvas);
    const GridSpec& canvas = a.canvas;
    EXPECT_EQ(a.report.omega, b.report.omega) << p;
    EXPECT_EQ(a.report.violations, 0);
    EXPECT_EQ(a.synthesis.valid_counts, b.synthesis.valid_counts) << p;
    ASSERT_EQ(a.synthesis.placements.size(), b.synthesis.placements.size());
    for (std::size_t i = 0; i < a.synthesis.placements.size(); ++i) {
      const Placement& x = a.synthesis.placements[i];
      const Placement& y = b.synthesis.placements[i];
      EXPECT_EQ(std::tie(x.ux, x.uy, x.empty, x.stitch), std::tie(y.ux, y.uy, y.empty, y.stitch))
          << "feature " << p << ", piece " << i;
      EXPECT_EQ(x.origin, y.origin);
    }
    // The opaque coverage that later features avoid, cell by cell.
    std::int64_t opaque = 0;
    for (int row = 0; row < canvas.height; ++row)
      for (int col = 0; col < canvas.width; ++col) {
        ASSERT_EQ(a.opaque.at(col, row), b.opaque.at(col, row)) << p << ": " << col << ", " << row;
        opaque += a.opaque.at(col, row);
      }
    EXPECT_GT(opaque, 100) << p;
    EXPECT_EQ(b.opaque.tiles_x() * b.opaque.tiles_y(), 1);
    const std::size_t all_tiles = std::size_t(a.opaque.tiles_x() * a.opaque.tiles_y());
    EXPECT_LE(a.opaque.tile_count(), all_tiles);
    if (p == 1) {  // the ring leaves its middle out
      EXPECT_LT(a.opaque.tile_count(), all_tiles / 2);
    }
    for (const auto v : foldover_mask(a.ribbon, canvas, Window::whole(canvas)).pixels) folded += v;
  }
  EXPECT_GT(folded, 20);  // the hairpin
  EXPECT_TRUE(lines[0][1].closed);
}

}  // namespace
}  // namespace tw
