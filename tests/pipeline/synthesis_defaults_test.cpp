// Synthesis width and delta from the exemplar when a class gives none (issue #11, item 2), and
// the quality numbers of every synthesized feature in report.json (item 6), on a straight road
// over a 640 m DEM with a 60 x 56 crop of the cobble exemplar.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "pipeline/run.hpp"
#include "synth/baseline.hpp"
#include "synth/exemplar.hpp"
#include "synth/exemplar_stats.hpp"
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
output: { dir: out }
synthesis_resolution: 1
features:
  roads:
    source: map.gpkg
    layer: roads
    kind: road
    width: 6
    synthesis: { exemplar: cobble.png, scale: 5 }
)";

class SynthesisDefaults : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_dem(dir_ / "dem.tif");
    test::write_layer(dir_ / "map.gpkg", "roads",
                      {{"LINESTRING (500050 5000300, 500590 5000330)", 6.0}});
    test::crop_raster(test::source_dir() / "samples/exemplars/cobble_edging_200x56.png",
                      dir_ / "cobble.png", "PNG", 60, 56);
  }

  // The report of a run with `overrides`, and the road's synthesis entry.
  nlohmann::json run(std::vector<Override> overrides, const std::string& out) {
    overrides.push_back({"output.dir", (dir_ / out).string()});
    run_pipeline(parse_pipeline(kPipeline, "p.yaml", dir_.path(), overrides));
    std::ifstream in(dir_ / out / "report.json");
    return nlohmann::json::parse(in);
  }

  test::TempDir dir_;
};

TEST_F(SynthesisDefaults, WidthAndDeltaComeFromTheExemplarAndReportJsonRecordsThem) {
  const ExemplarStats stats = exemplar_stats(load_exemplar((dir_ / "cobble.png").string()));
  const double width = suggested_width(stats, 5.0), delta = suggested_delta(stats, 5.0);
  ASSERT_GT(width, 1.0);
  ASSERT_GT(delta, 1.0);
  ASSERT_NE(delta, 4.0);  // not the old default

  const nlohmann::json derived = run({}, "derived");
  const auto& road = derived["classes"][0];
  EXPECT_DOUBLE_EQ(road["delta_m"].get<double>(), delta);
  const auto& s = road["features"][0]["synthesis"];
  EXPECT_DOUBLE_EQ(s["width_m"].get<double>(), width);
  EXPECT_EQ(s["width_from"], "exemplar");
  EXPECT_DOUBLE_EQ(s["delta_m"].get<double>(), delta);
  EXPECT_EQ(s["delta_from"], "exemplar");
  EXPECT_EQ(s["min_coverage_from"], "exemplar");
  // The pieces are δ long: the ribbon of the line at the derived width and delta.
  const Ribbon ribbon =
      make_ribbon(Curve{{{500050, 5000300}, {500590, 5000330}}, false}, {width, delta, 0.0});
  EXPECT_EQ(road["features"][0]["pieces"].get<std::size_t>(), ribbon.pieces.size());

  // Item 6: the quality numbers, each checked against its definition. The parametric baseline
  // on the same ribbon, recomputed here.
  EXPECT_NEAR(s["coverage_ratio"].get<double>(),
              s["mean_coverage"].get<double>() / s["natural_coverage"].get<double>(), 1e-9);
  EXPECT_GE(s["coverage_ratio"].get<double>(), 0.8);
  EXPECT_LE(s["mean_seam_cost_stitched"].get<double>(), s["mean_seam_cost"].get<double>());
  const Synthesis baseline =
      parametric_baseline(load_exemplar((dir_ / "cobble.png").string()), ribbon, 5.0);
  EXPECT_NEAR(s["parametric_seam_cost"].get<double>(), baseline.mean_seam_cost, 1e-9);
  EXPECT_LT(s["mean_seam_cost_stitched"].get<double>(), s["parametric_seam_cost"].get<double>());

  // Given values are kept and recorded as the config's; `width: feature` is the road's 6 m.
  const nlohmann::json given = run(
      {{"features.roads.synthesis.width", "8"}, {"features.roads.synthesis.delta", "7"}}, "given");
  const auto& g = given["classes"][0]["features"][0]["synthesis"];
  EXPECT_DOUBLE_EQ(g["width_m"].get<double>(), 8.0);
  EXPECT_EQ(g["width_from"], "config");
  EXPECT_DOUBLE_EQ(g["delta_m"].get<double>(), 7.0);
  EXPECT_EQ(g["delta_from"], "config");
  EXPECT_DOUBLE_EQ(given["classes"][0]["delta_m"].get<double>(), 7.0);
  const nlohmann::json feature = run({{"features.roads.synthesis.width", "feature"}}, "feature");
  const auto& f = feature["classes"][0]["features"][0]["synthesis"];
  EXPECT_DOUBLE_EQ(f["width_m"].get<double>(), 6.0);
  EXPECT_EQ(f["width_from"], "feature");
  EXPECT_EQ(f["delta_from"], "exemplar");
}

}  // namespace
}  // namespace tw
