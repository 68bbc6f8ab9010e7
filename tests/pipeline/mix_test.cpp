// Several exemplars mixed within one feature in pipelines (issue #11 item 4, docs/pipeline.md
// `choose: mix`): the keys and their errors, bind rules evaluated by OGR on the class's layer
// and near its junctions (read back from the placements), report.json's counts, and the cache
// key's parts.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cache_world.hpp"
#include "core/error.hpp"
#include "core/segment_distance.hpp"
#include "core/warnings.hpp"
#include "pipeline/config.hpp"
#include "pipeline/methods/patterns/pattern_report.hpp"
#include "pipeline/methods/patterns/synthesis_cache.hpp"
#include "pipeline/run.hpp"
#include "ribbon/ribbon.hpp"
#include "synth/exemplar_mix.hpp"
#include "synth/placements_io.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// Two roads crossing near (500320, 5000315): FID 1 asphalt west to east, FID 2 sett south to
// north. Lanes elsewhere, setts on the sett road, the crossing pattern near the junction.
constexpr const char* kPipeline = R"(
version: 1
seed: 5
heightfield: dem.tif
resolution: 10
output: { dir: out, exr: false, geotiff: true, preview: false }
synthesis_resolution: 1
features:
  roads:
    source: map.gpkg
    layer: roads
    kind: road
    width: 6
    synthesis:
      exemplar: [lanes.png, sett.png, crossing.png]
      choose: mix
      switch_cost: 8
      bind:
        - { exemplar: sett.png, tags: { surface: [sett] } }
        - { exemplar: 2, near_junction: 16 }
      width: 10                      # 40 texels: clear rows above and below the lanes band (14..49)
      scale: 4
      delta: 6
)";

constexpr double kNear = 16.0;

class MixWorld : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_dem(dir_ / "dem.tif");
    test::VectorFeature asphalt("LINESTRING (500050 5000300, 500590 5000330)", 6.0);
    asphalt.text = {{"surface", "asphalt"}};
    test::VectorFeature sett("LINESTRING (500310 5000050, 500330 5000590)", 6.0);
    sett.text = {{"surface", "sett"}};
    test::write_layer(dir_ / "map.gpkg", "roads", {asphalt, sett});
    const fs::path samples = test::source_dir() / "samples/exemplars";
    for (const auto& [from, to] :
         std::vector<std::pair<std::string, std::string>>{{"road_lanes_240x64", "lanes"},
                                                          {"crossing_240x64", "crossing"},
                                                          {"cobble_edging_200x56", "sett"}}) {
      const int height = to == "sett" ? 56 : 64;
      test::crop_raster(samples / (from + ".png"), dir_ / (to + ".png"), "PNG", 100, height);
      test::crop_raster(samples / (from + "_height.tif"), dir_ / (to + "_height.tif"), "GTiff", 100,
                        height);
    }
  }

  PipelineConfig config(std::vector<Override> overrides = {}) const {
    overrides.push_back({"output.dir", (dir_ / "out").string()});
    return parse_pipeline(kPipeline, "mix.yaml", dir_.path(), overrides);
  }

  std::string parse_error(const std::string& key, const std::string& value) const {
    try {
      config({{key, value}});
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  }

  nlohmann::json report() const {
    std::ifstream in(dir_ / "out" / "report.json");
    return nlohmann::json::parse(in);
  }
  // The first class's features, by value: a range-for over report()[...] would iterate a part
  // of a temporary destroyed before the loop's body (C++20).
  nlohmann::json first_class_features() const { return report()["classes"][0]["features"]; }

  test::TempDir dir_;
};

TEST_F(MixWorld, ConfigReadsChooseMixSwitchCostAndBindings) {
  const PipelineConfig c = config();
  const SynthesisConfig& s = *method_options<SynthesisConfig>(c.features[0], kPatternsMethodName);
  EXPECT_EQ(s.choice, ExemplarChoice::mix);
  EXPECT_EQ(s.switch_cost, 8);
  ASSERT_EQ(s.bind.size(), 2u);
  EXPECT_EQ(s.bind[0].exemplar, 1u);  // by path
  ASSERT_EQ(s.bind[0].tags.size(), 1u);
  EXPECT_EQ(s.bind[0].tags[0].key, "surface");
  EXPECT_EQ(s.bind[0].tags[0].values, (std::vector<std::string>{"sett"}));
  EXPECT_DOUBLE_EQ(s.bind[0].near_junction, 0.0);
  EXPECT_EQ(s.bind[1].exemplar, 2u);  // by index
  EXPECT_DOUBLE_EQ(s.bind[1].near_junction, kNear);
  EXPECT_EQ(s.bind[1].key, "features.roads.synthesis.bind.1");
  const PipelineConfig w =
      config({{"features.roads.synthesis.bind", "[{exemplar: 0, where: \"surface = 'x'\"}]"}});
  EXPECT_EQ(method_options<SynthesisConfig>(w.features[0], kPatternsMethodName)->bind[0].where,
            "surface = 'x'");
}

TEST_F(MixWorld, ConfigErrorsNameTheKey) {
  EXPECT_THAT(parse_error("features.roads.synthesis.choose", "best"),
              HasSubstr("features.roads.synthesis.switch_cost: only with choose: mix"));
  EXPECT_THAT(parse_error("features.roads.synthesis.choose", "mixed"),
              HasSubstr("unknown choice 'mixed', expected seed, best or mix"));
  EXPECT_THAT(parse_error("features.roads.synthesis.switch_cost", "-1"),
              HasSubstr("features.roads.synthesis.switch_cost: must be in [0, "));
  EXPECT_THAT(parse_error("features.roads.synthesis.bind", "[{exemplar: 3, near_junction: 5}]"),
              HasSubstr("features.roads.synthesis.bind.0.exemplar: exemplar 3 of a list of 3"));
  EXPECT_THAT(parse_error("features.roads.synthesis.bind", "[{exemplar: deck.png, where: x}]"),
              HasSubstr("bind.0.exemplar: 'deck.png' is not one of the class's exemplars "
                        "(lanes.png, sett.png, crossing.png)"));
  EXPECT_THAT(parse_error("features.roads.synthesis.bind", "[{exemplar: 0}]"),
              HasSubstr("features.roads.synthesis.bind.0: a binding needs where, tags or "
                        "near_junction"));
  EXPECT_THAT(parse_error("features.roads.synthesis.bind", "[{exemplar: 0, near: 5}]"),
              HasSubstr("features.roads.synthesis.bind.0.near: unknown key"));
  EXPECT_THAT(parse_error("features.roads.synthesis.bind", "[{exemplar: 0, near_junction: -2}]"),
              HasSubstr("features.roads.synthesis.bind.0.near_junction"));
  EXPECT_THAT(parse_error("features.roads.synthesis.bind", "{exemplar: 0}"),
              HasSubstr("features.roads.synthesis.bind: expected a list"));
}

// OGR judges the where clause; a bad one fails the run naming the rule.
TEST_F(MixWorld, BadWhereClauseNamesTheRule) {
  try {
    run_pipeline(config(
        {{"features.roads.synthesis.bind.0", "{exemplar: 1, where: \"no_such_column = 1\"}"}}));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("features.roads.synthesis.bind.0: "));
    EXPECT_THAT(e.what(), HasSubstr("no_such_column"));
  }
}

// The crossing point of the two roads (both straight).
Vec2 crossing_point() {
  const Vec2 a0{500050, 5000300}, a1{500590, 5000330}, b0{500310, 5000050}, b1{500330, 5000590};
  const Vec2 r = a1 - a0, s = b1 - b0;
  const double t = ((b0.x - a0.x) * s.y - (b0.y - a0.y) * s.x) / (r.x * s.y - r.y * s.x);
  return a0 + r * t;
}

TEST_F(MixWorld, BoundStretchesAndJunctionsUseTheirExemplarAndTheReportCountsThem) {
  const RunReport run = run_pipeline(config());
  EXPECT_EQ(detail::pattern_violations(run), 0);
  const nlohmann::json json = report();
  const auto& features = json["classes"][0]["features"];
  ASSERT_EQ(features.size(), 2u);
  const Vec2 junction = crossing_point();
  for (const auto& f : features) {
    const std::int64_t fid = f["fid"];
    SCOPED_TRACE(fid == 1 ? "asphalt road" : "sett road");
    const auto& s = f["synthesis"];
    const Synthesis placed =
        load_placements((dir_ / "out" / s["placements"].get<std::string>()).string());
    ASSERT_TRUE(placed.mix.has_value());
    // The synthesis ribbon, as the pipeline slices it (width 10, delta 6).
    const Curve line = fid == 1 ? Curve{{{500050, 5000300}, {500590, 5000330}}, false}
                                : Curve{{{500310, 5000050}, {500330, 5000590}}, false};
    const Ribbon ribbon = make_ribbon(line, {10.0, 6.0});
    ASSERT_EQ(placed.placements.size(), ribbon.pieces.size());
    std::vector<int> counts(3, 0);
    int switches = 0, near = 0, previous = -1;
    for (std::size_t i = 0; i < ribbon.pieces.size(); ++i) {
      const Placement& p = placed.placements[i];
      if (p.empty) {  // the junction disc may leave a piece no room
        previous = -1;
        continue;
      }
      const Piece& piece = ribbon.pieces[i];
      const double d = distance_to_segment(junction, lerp(piece.top_left, piece.bottom_left, 0.5),
                                           lerp(piece.top_right, piece.bottom_right, 0.5));
      const int expected = fid == 2 ? 1 : d <= kNear ? 2 : 0;
      if (std::abs(d - kNear) > 0.5) {
        EXPECT_EQ(p.exemplar, expected) << "piece " << i << ", " << d;
      }
      near += fid == 1 && expected == 2 ? 1 : 0;
      ++counts[std::size_t(p.exemplar)];
      if (previous >= 0 && previous != p.exemplar) ++switches;
      previous = p.exemplar;
    }
    if (fid == 1) {
      EXPECT_GE(near, 3);
    }
    EXPECT_EQ(s["mix"]["pieces_per_exemplar"].get<std::vector<int>>(), counts);
    EXPECT_EQ(s["mix"]["switches"].get<int>(), switches);
    EXPECT_EQ(s["mix"]["switch_cost"].get<int>(), 8);
    ASSERT_EQ(s["mix"]["exemplars"].size(), 3u);
    EXPECT_THAT(s["mix"]["exemplars"][1].get<std::string>(), HasSubstr("sett.png"));
    EXPECT_EQ(s["violations"], 0);
  }
}

// The key changes with the choice, the switching cost, the rules and their verdicts, and the
// junctions the feature meets; a rerun with another switch_cost rebuilds ("config changed").
TEST_F(MixWorld, CacheKeyCoversChoiceSwitchCostAndBindings) {
  const PipelineConfig base = config();
  Warnings warnings;
  detail::SynthesisCache cache(std::nullopt, warnings);
  LineFeature line;
  line.fid = 1;
  line.points = {{500050, 5000300}, {500590, 5000330}};
  line.width = 6.0;
  const GridSpec canvas{600, 60, 500040, 5000340, 1, 1};
  const std::vector<PieceBinding> rules = {{1, false, 0.0}, {2, true, kNear}};
  const std::vector<Vec2> junctions = {crossing_point()};
  const auto key = [&](const PipelineConfig& c, const std::vector<PieceBinding>& b,
                       const std::vector<Vec2>& j) {
    return cache.key(c, c.features[0], line, 7, canvas, AvoidanceInputs{}, {}, b, j).combined();
  };
  const ContentHash reference = key(base, rules, junctions);
  EXPECT_EQ(key(config(), rules, junctions), reference);  // deterministic
  PipelineConfig by_seed = base;
  method_options<SynthesisConfig>(by_seed.features[0], kPatternsMethodName).choice =
      ExemplarChoice::by_seed;
  EXPECT_NE(key(by_seed, rules, junctions), reference);
  EXPECT_NE(key(config({{"features.roads.synthesis.switch_cost", "9"}}), rules, junctions),
            reference);
  EXPECT_NE(
      key(config({{"features.roads.synthesis.bind.1.near_junction", "15"}}), rules, junctions),
      reference);
  EXPECT_NE(key(config({{"features.roads.synthesis.bind.0.tags", "{surface: [paving]}"}}), rules,
                junctions),
            reference);
  EXPECT_NE(key(config({{"features.roads.synthesis.bind.1.exemplar", "0"}}), rules, junctions),
            reference);
  EXPECT_NE(key(base, {{1, true, 0.0}, {2, true, kNear}}, junctions), reference);  // verdict
  EXPECT_NE(key(base, rules, {}), reference);
  EXPECT_NE(key(base, rules, {crossing_point() + Vec2{1.0, 0.0}}), reference);
  EXPECT_NE(cache
                .key(base, base.features[0], line, 7, canvas, AvoidanceInputs{}, {}, rules,
                     junctions, 500)
                .combined(),
            reference);  // the atlas's gap

  RunOptions options;
  options.cache_dir = dir_ / "cache";
  run_pipeline(config(), options);
  run_pipeline(config(), options);
  for (const auto& f : first_class_features()) EXPECT_EQ(f["cache"]["why"], "unchanged");
  run_pipeline(config({{"features.roads.synthesis.switch_cost", "40"}}), options);
  for (const auto& f : first_class_features()) {
    EXPECT_EQ(f["cache"]["status"], "rebuilt");
    EXPECT_EQ(f["cache"]["why"], "config changed");
  }
  // Reused entries report the mix as built.
  run_pipeline(config({{"features.roads.synthesis.switch_cost", "40"}}), options);
  for (const auto& f : first_class_features()) {
    EXPECT_EQ(f["cache"]["status"], "reused");
    EXPECT_EQ(f["synthesis"]["mix"]["switch_cost"], 40);
    EXPECT_EQ(f["synthesis"]["mix"]["exemplars"].size(), 3u);
  }
}

// A mix's atlas keeps the class's widest line's pieces apart (mix_gap), and the placements are
// atlas columns: a line made wider far from the others moves every exemplar of the atlas, so
// every synthesis of the class is rebuilt, and the run equals one without a cache.
TEST_F(MixWorld, AWiderLineElsewhereMovesTheAtlasAndRebuildsTheWholeClass) {
  const auto write_map = [&](double far_width) {
    test::VectorFeature asphalt("LINESTRING (500050 5000300, 500590 5000330)", 10.0);
    asphalt.text = {{"surface", "asphalt"}};
    test::VectorFeature sett("LINESTRING (500310 5000050, 500330 5000590)", 10.0);
    sett.text = {{"surface", "sett"}};
    // 270 m north of FID 1 and 60 m west of FID 2's end: no canvas of theirs reaches it.
    test::VectorFeature far("LINESTRING (500050 5000600, 500250 5000600)", far_width);
    far.text = {{"surface", "asphalt"}};
    fs::remove(dir_ / "map.gpkg");
    test::write_layer(dir_ / "map.gpkg", "roads", {asphalt, sett, far});
  };
  // Each line's own width, so that the widest line sets the atlas's gap (scale 4, delta 6).
  ASSERT_NE(mix_gap(4.0, 6.0, 10.0), mix_gap(4.0, 6.0, 14.0));
  const std::vector<Override> own_width = {{"features.roads.width_attribute", "width"},
                                           {"features.roads.synthesis.width", "feature"}};
  RunOptions cached;
  cached.cache_dir = dir_ / "cache";
  write_map(10.0);
  run_pipeline(config(own_width), cached);
  write_map(14.0);
  run_pipeline(config(own_width), cached);
  const nlohmann::json features = first_class_features();
  ASSERT_EQ(features.size(), 3u);
  for (const auto& f : features) {
    EXPECT_EQ(f["cache"]["status"], "rebuilt") << f["fid"];
    if (f["fid"] == 3) continue;  // its own width changed
    EXPECT_EQ(f["cache"]["why"], "config changed") << f["fid"];
  }
  fs::rename(dir_ / "out", dir_ / "cached");
  run_pipeline(config(own_width));
  EXPECT_GT(test::expect_same_output_files(dir_ / "cached", dir_ / "out"), 5u);
}

}  // namespace
}  // namespace tw
