// Curve synthesis along grown lines (docs/pipeline.md, "Grown classes"; issue #13 B4): a hedge
// class grown beside a road is dressed with the hedge exemplar. Its pattern lies along the grown
// lines in its own splat channel, keeps off the road's pattern (zero forbidden pixels), comes out
// the same bytes twice and on OpenCL, and lines that cannot hold a piece, or whose pieces have no
// room, are counted in report.json instead of failing the run.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/warnings.hpp"
#include "layers/write.hpp"
#include "pipeline/methods/grown/grown_report.hpp"
#include "pipeline/methods/patterns/pattern_report.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/run.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

// 100 x 100 cells of 2 m: x 500000..500200, y 4999800..5000000. A road runs north-south through
// x = 500100 with a lane pattern; hedges are grown on both sides of it and dressed after it.
constexpr const char* kWorld = R"(
version: 1
seed: 4
generate: { width: 100, height: 100, pixel_size: 2, relief: 20 }
output: { dir: out, exr: true, geotiff: false, preview: false }
precedence: [roads, hedges]
features:
  roads:
    source: map.gpkg
    layer: roads
    kind: road
    width: 6
    synthesis: { exemplar: lanes.png, delta: 6 }
  hedges:
    kind: hedge
    grow: { element: hedge.json, region: [500010, 4999810, 500190, 4999990], max_ornaments: 6 }
    synthesis: { exemplar: hedge.png, delta: 3 }
)";

class GrownSynthesis : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_layer(dir_ / "map.gpkg", "roads",
                      {{"LINESTRING (500100 4999800, 500100 5000000)"}});
    const fs::path samples = test::source_dir() / "samples";
    fs::copy_file(samples / "ornaments/hedge.json", dir_ / "hedge.json");
    fs::copy_file(samples / "exemplars/hedge_192x48.png", dir_ / "hedge.png");
    test::crop_raster(samples / "exemplars/road_lanes_240x64.png", dir_ / "lanes.png", "PNG", 96,
                      64);
  }

  RunReport run(const std::string& out, std::vector<Override> overrides = {},
                RunOptions options = {}) const {
    overrides.push_back({"output.dir", (dir_ / out).string()});
    return run_pipeline(parse_pipeline(kWorld, "world.yaml", dir_.path(), overrides), options);
  }

  nlohmann::json report_of(const std::string& out) const {
    return nlohmann::json::parse(test::read_file(dir_ / out / "report.json"));
  }

  test::TempDir dir_;
};

const Raster<float>& band_of(const ExrContents& exr, const std::string& channel) {
  const auto it = std::find(exr.channels.begin(), exr.channels.end(), channel);
  if (it == exr.channels.end()) throw std::runtime_error("no channel " + channel);
  return exr.bands[std::size_t(it - exr.channels.begin())];
}

TEST_F(GrownSynthesis, HedgePatternLiesAlongTheGrownLinesOffTheRoadsPattern) {
  const RunReport report = run("a");
  EXPECT_EQ(detail::pattern_violations(report), 0);
  const FeatureClassReport& hedges = report.classes.at(1);
  const detail::GrowthReport* grow = detail::growth_report(report, 1);
  ASSERT_TRUE(grow && detail::grown_synthesis_report(report, 1));
  const detail::GrownSynthesisReport& dressed = *detail::grown_synthesis_report(report, 1);
  std::printf("hedges: %d lines, %d dressed, %d no room, %d short\n", grow->lines, dressed.dressed,
              dressed.no_room, grow->short_lines);
  EXPECT_GE(grow->lines, 10);
  EXPECT_GT(dressed.dressed, grow->lines / 2);
  EXPECT_EQ(dressed.dressed + dressed.no_room + grow->short_lines, grow->lines);
  for (std::size_t i = 0; i < hedges.features.size(); ++i) {
    const FeatureReport& f = hedges.features[i];
    const FeatureSynthesisReport* synthesis = detail::synthesis_report(report, 1, i);
    if (f.pieces == 0) {
      EXPECT_FALSE(synthesis) << f.fid;
      continue;
    }
    ASSERT_TRUE(synthesis) << f.fid;
    EXPECT_EQ(synthesis->violations, 0) << f.fid;
    EXPECT_THAT(synthesis->exemplar, ::testing::EndsWith("hedge.png"));
  }
  for (const Warning& w : report.warnings) EXPECT_NE(w.code, "shorter_than_delta") << w.message;
  const nlohmann::json json = report_of("a");
  EXPECT_EQ(json["pattern_violations"], 0);
  EXPECT_EQ(json["classes"][1]["grow"]["synthesis"]["dressed"].get<int>(), dressed.dressed);
  EXPECT_EQ(json["classes"][1]["grow"]["short_lines"].get<int>(), grow->short_lines);

  // The hedge channel is non-zero along the dressed lines: at most of their vertices, within a
  // pixel (the pattern is about 2.5 m wide on a 2 m grid; junction discs leave joints bare).
  Warnings warnings;
  const WorldPlan plan = plan_world(
      parse_pipeline(kWorld, "world.yaml", dir_.path(), {{"output.dir", (dir_ / "p").string()}}),
      {}, warnings);
  const ExrContents splat = read_exr(dir_ / "a/splat.exr");
  const Raster<float>& hedge = band_of(splat, "splat.hedges_pattern");
  const Raster<float>& lanes = band_of(splat, "splat.roads_pattern");
  const GridSpec& grid = plan.grid;
  int on = 0, vertices = 0;
  for (std::size_t i = 0; i < plan.lines.at(1).size(); ++i) {
    const FeatureSynthesisReport* synthesis = detail::synthesis_report(report, 1, i);
    if (!synthesis || synthesis->empty_pieces == hedges.features[i].pieces) continue;
    for (const Vec2 p : plan.lines[1][i].points) {
      const int col = int((p.x - grid.origin_x) / grid.pixel_width);
      const int row = int((grid.origin_y - p.y) / grid.pixel_height);
      float most = 0.0f;
      for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc)
          if (col + dc >= 0 && col + dc < hedge.width && row + dr >= 0 && row + dr < hedge.height)
            most = std::max(most, hedge.at(col + dc, row + dr));
      on += most > 0.0f;
      ++vertices;
    }
  }
  std::printf("hedge channel non-zero near %d of %d vertices of dressed lines\n", on, vertices);
  ASSERT_GT(vertices, 0);
  EXPECT_GT(on, vertices * 6 / 10);
  // Both patterns are there, the hedge one nowhere on the road's centre column.
  double lanes_sum = 0.0;
  for (int row = 0; row < lanes.height; ++row) {
    lanes_sum += lanes.at(50, row);
    EXPECT_EQ(hedge.at(50, row), 0.0f) << row;
  }
  EXPECT_GT(lanes_sum, 10.0);
}

TEST_F(GrownSynthesis, SameBytesTwiceAndOnOpenCl) {
  run("a");
  run("b");
  RunOptions opencl;
  opencl.backend = "opencl";
  run("c", {}, opencl);
  EXPECT_THAT(
      report_of("c")["classes"][1]["features"][0]["synthesis"]["backend"].get<std::string>(),
      ::testing::StartsWith("opencl"));
  for (const char* file :
       {"splat.exr", "height.exr", "ornaments.gpkg", "placements/hedges_1.json"}) {
    const std::string a = test::read_file(dir_ / "a" / file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_TRUE(a == test::read_file(dir_ / "b" / file)) << file << " twice";
    EXPECT_TRUE(a == test::read_file(dir_ / "c" / file)) << file << " on OpenCL";
  }
}

TEST_F(GrownSynthesis, ShortLinesAndLinesWithoutRoomAreCountedNotErrors) {
  // Pieces of 15 m: the shorter grown lines hold none.
  const RunReport long_pieces = run("long", {{"features.hedges.synthesis.delta", "15"}});
  const detail::GrowthReport& g = *detail::growth_report(long_pieces, 1);
  const detail::GrownSynthesisReport& gs = *detail::grown_synthesis_report(long_pieces, 1);
  EXPECT_GT(g.short_lines, 0);
  EXPECT_EQ(gs.dressed + gs.no_room + g.short_lines, g.lines);
  for (const Warning& w : long_pieces.warnings) EXPECT_NE(w.code, "shorter_than_delta");
  // Ribbons 8 m wide, four times the hedge: later lines find their pieces under the patterns of
  // the lines grown beside them (and the road's), and some have no room at all: left bare.
  const RunReport too_wide = run("wide", {{"features.hedges.synthesis.width", "8"}});
  const detail::GrowthReport& w = *detail::growth_report(too_wide, 1);
  const detail::GrownSynthesisReport& ws = *detail::grown_synthesis_report(too_wide, 1);
  EXPECT_EQ(ws.dressed + ws.no_room + w.short_lines, w.lines);
  EXPECT_GT(ws.no_room, 0);
  EXPECT_EQ(report_of("wide")["classes"][1]["grow"]["synthesis"]["no_room"].get<int>(), ws.no_room);
  // A read line class without room still fails (patterns_test); a grown one only counts it.
  EXPECT_EQ(detail::pattern_violations(too_wide), 0);
}

// Issue #24 item 8: a grown class none of whose lines took its pattern is a warning
// (grown_undressed, naming the class and the count), so --strict fails the run, writing nothing.
TEST_F(GrownSynthesis, AClassWithNoLineDressedWarnsAndFailsUnderStrict) {
  // Every piece must be 99 % opaque: the hedge exemplar's fringes leave no position valid.
  const std::vector<Override> none_fit = {{"features.hedges.synthesis.min_coverage", "0.99"}};
  const RunReport report = run("bare", none_fit);
  const detail::GrownSynthesisReport& g = *detail::grown_synthesis_report(report, 1);
  EXPECT_EQ(g.dressed, 0);
  ASSERT_GT(g.no_room, 0);
  const auto warning = std::find_if(report.warnings.begin(), report.warnings.end(),
                                    [](const Warning& w) { return w.code == "grown_undressed"; });
  ASSERT_NE(warning, report.warnings.end());
  EXPECT_EQ(warning->subject, "features.hedges");
  EXPECT_THAT(warning->message,
              ::testing::HasSubstr(fmt::format("dressed 0 of {} grown lines", g.no_room)));
  RunOptions strict;
  strict.strict = true;
  try {
    run("strict", none_fit, strict);
    FAIL() << "--strict passed";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("strict: "));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("nothing written"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "strict"));
  // A dressed class warns about nothing of the kind.
  const RunReport dressed = run("dressed");
  for (const Warning& w : dressed.warnings) EXPECT_NE(w.code, "grown_undressed");
}

// `choose: mix` on a grown class: its lines are grown and its source is the region's polygons, so
// a where or tags rule would ask the polygons' layer and bind the grown lines whose numbers happen
// to be the selected polygons' FIDs (polygon 1's where bound grown line 1, wherever it lay). It
// is refused when the pipeline is read, naming the rule, as for network classes; a near_junction
// rule is read as before.
TEST_F(GrownSynthesis, MixRefusesWhereAndTagsRulesOnGrownLines) {
  // Two fields west and east of the road; field 1 carries crop=wheat.
  test::write_layer(dir_ / "fields.gpkg", "fields",
                    {{"POLYGON ((500010 4999810, 500090 4999810, 500090 4999990, 500010 4999990, "
                      "500010 4999810))",
                      0.0,
                      {{"crop", "wheat"}}},
                     {"POLYGON ((500110 4999810, 500190 4999810, 500190 4999990, 500110 4999990, "
                      "500110 4999810))",
                      0.0,
                      {{"crop", "barley"}}}});
  const std::string exemplars =
      "[" + (dir_ / "hedge.png").string() + ", " + (dir_ / "lanes.png").string() + "]";
  const auto config = [&](const std::string& rule, bool polygons) {
    std::vector<Override> overrides = {
        {"features.hedges.synthesis.exemplar", exemplars},
        {"features.hedges.synthesis.choose", "mix"},
        {"features.hedges.synthesis.bind", "[{exemplar: 1, " + rule + "}]"},
        {"output.dir", (dir_ / "m").string()}};
    std::string text = kWorld;
    if (polygons) {  // the region is the fields layer, not a box
      const std::string box = ", region: [500010, 4999810, 500190, 4999990]";
      text.replace(text.find(box), box.size(), "");
      const std::string grow = "    grow:";
      text.replace(text.find(grow), grow.size(),
                   "    source: fields.gpkg\n    layer: fields\n    grow:");
    }
    return parse_pipeline(text, "world.yaml", dir_.path(), overrides);
  };
  for (const bool polygons : {false, true})
    for (const std::string rule : {"where: \"crop = 'wheat'\"", "tags: {crop: [wheat]}"}) {
      std::string message = "no error";
      try {
        config(rule, polygons);
      } catch (const Error& e) {
        message = e.what();
      }
      EXPECT_THAT(message, ::testing::HasSubstr("features.hedges.synthesis.bind.0"))
          << rule << (polygons ? " (polygons)" : " (box)");
      EXPECT_THAT(message, ::testing::HasSubstr("bind them by near_junction"))
          << rule << (polygons ? " (polygons)" : " (box)");
    }
  // A near_junction rule is read (grown lines meet at junctions).
  const PipelineConfig near = config("near_junction: 6", true);
  EXPECT_EQ(method_options<SynthesisConfig>(near.features.at(1), kPatternsMethodName)
                ->bind.at(0)
                .near_junction,
            6.0);
}

}  // namespace
}  // namespace tw
