// pipelines/osm.yaml end to end (samples/olinda.osm over the Olinda DEM): tag selections,
// widths from the OSM tag table, a bridge over the river and a tunnel through the hill.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "geo/features.hpp"
#include "geo/heightfield.hpp"
#include "geo/resample.hpp"
#include "pipeline/run.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

class OsmRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    out_ = new test::TempDir;
    config_ = new PipelineConfig(load_pipeline(test::source_dir() / "pipelines/osm.yaml",
                                               {{"output.dir", out_->path().string()}}));
    run_pipeline(*config_);
    std::ifstream in(out_->path() / "report.json");
    report_ = new nlohmann::json(nlohmann::json::parse(in));
    HeightfieldOptions options;
    options.resolution = config_->resolution;
    options.resampling = config_->resampling;  // the DEM as the run reads it
    original_ = new Heightfield(read_heightfield(config_->heightfield->string(), options));
    shaped_ = new Heightfield(read_heightfield((out_->path() / "height.tif").string(), {}));
  }
  static void TearDownTestSuite() {
    delete shaped_;
    delete original_;
    delete report_;
    delete config_;
    delete out_;
  }

  // The roads' line of OSM way `fid`, in the grid's metres.
  static LineFeature road(std::int64_t fid) {
    const FeatureClassConfig& roads = config_->features.back();
    LineClassSpec spec;
    spec.name = roads.name;
    spec.source = {roads.source.string(), roads.layer, selection_where(roads.tags, roads.where)};
    spec.osm_widths = true;
    for (LineFeature& line : read_line_features(spec, *original_))
      if (line.fid == fid) return line;
    ADD_FAILURE() << "no way " << fid;
    return {};
  }
  static const nlohmann::json& reported(const std::string& class_name, std::int64_t fid) {
    for (const auto& c : (*report_)["classes"])
      if (c["name"] == class_name)
        for (const auto& f : c["features"])
          if (f["fid"] == fid) return f;
    throw std::runtime_error("not reported");
  }
  static double shaped_at(Vec2 p) {
    return sample_height_bilinear(shaped_->height, shaped_->grid, p);
  }

  // Checks that every cell whose centre lies within 6 m of the segment (under a 7 m deck and its
  // edges) a-b, between `from` and `to` metres along it, is exactly as in the DEM; returns how many
  // it checked.
  static int expect_untouched(Vec2 a, Vec2 b, double from, double to) {
    const GridSpec& grid = original_->grid;
    const Vec2 ab = b - a;
    const double length = std::sqrt(dot(ab, ab));
    int checked = 0;
    for (int row = 0; row < grid.height; ++row)
      for (int col = 0; col < grid.width; ++col) {
        const Vec2 p = grid.pixel_centre_world(col, row);
        const double along = dot(p - a, ab) / length;
        const double across = std::abs(cross(ab, p - a)) / length;
        if (across > 6.0 || along < from || along > to) continue;
        EXPECT_EQ(shaped_->height.at(col, row), original_->height.at(col, row))
            << "cell " << col << ", " << row << " at " << along << " m along";
        ++checked;
      }
    return checked;
  }

  static test::TempDir* out_;
  static PipelineConfig* config_;
  static nlohmann::json* report_;
  static Heightfield* original_;
  static Heightfield* shaped_;
};
test::TempDir* OsmRun::out_ = nullptr;
PipelineConfig* OsmRun::config_ = nullptr;
nlohmann::json* OsmRun::report_ = nullptr;
Heightfield* OsmRun::original_ = nullptr;
Heightfield* OsmRun::shaped_ = nullptr;

TEST_F(OsmRun, TagsSelectTheWaysAndTheTagTableGivesKindsAndWidths) {
  std::map<std::string, std::map<std::int64_t, double>> widths;
  std::map<std::string, std::string> kinds;
  for (const auto& c : (*report_)["classes"]) {
    kinds[c["name"]] = c["kind"];
    for (const auto& f : c["features"]) widths[c["name"]][f["fid"]] = f["width_m"];
  }
  EXPECT_EQ(kinds["ridges"], "ridge");
  EXPECT_EQ(kinds["rivers"], "river");
  EXPECT_EQ(kinds["roads"], "road");
  using Widths = std::map<std::int64_t, double>;
  EXPECT_EQ(widths["ridges"], (Widths{{5001, 40.0}}));               // natural=ridge
  EXPECT_EQ(widths["rivers"], (Widths{{1001, 20.0}, {1002, 3.0}}));  // river, stream
  EXPECT_EQ(widths["roads"], (Widths{{2001, 7.0},
                                     {2002, 7.0},
                                     {2003, 7.0},  // highway=primary
                                     {3001, 6.5},
                                     {3002, 6.5},
                                     {3003, 6.5},     // secondary
                                     {4001, 5.5},     // residential
                                     {4002, 6.0}}));  // width=6 m
  EXPECT_EQ(reported("roads", 2002)["structure"], "bridge");
  EXPECT_EQ(reported("roads", 2002)["layer"], 1);
  EXPECT_EQ(reported("roads", 3002)["structure"], "tunnel");
  EXPECT_EQ(reported("roads", 3002)["layer"], -1);
  EXPECT_FALSE(reported("roads", 2001).contains("structure"));
  // The rivers were drawn by hand over the 90 m DEM: where their never-rising surface would
  // cut deeper than max_carve's default (2 x depth), they meet the terrain and say so. Nothing
  // else warns.
  EXPECT_EQ((*report_)["warning_count"], 2);
  for (const auto& w : (*report_)["warnings"]) {
    EXPECT_EQ(w["code"], "carve_limited") << w.dump();
    EXPECT_EQ(w["subject"], "features.rivers") << w.dump();
  }
}

TEST_F(OsmRun, TheRiverIsCarvedUnderTheBridgeAndTheDeckSpansTheGap) {
  const LineFeature bridge = road(2002);
  ASSERT_EQ(bridge.points.size(), 2u);
  const Vec2 start = bridge.points.front(), end = bridge.points.back();
  const Vec2 middle = (start + end) * 0.5;  // where the bridge crosses the river
  const double length = distance(start, end);
  EXPECT_NEAR(length, 200.0, 1.0);
  // The river below stays carved: its bed lies depth (2.5 m) below a surface that is at most
  // the terrain.
  const double river_bed = shaped_at(middle);
  EXPECT_LE(river_bed, sample_height_bilinear(original_->height, original_->grid, middle) - 2.0);
  // The deck's ends are the graded approaches' heights there (within the grade over a cell).
  const auto& deck = reported("roads", 2002)["deck_m"];
  ASSERT_EQ(deck.size(), 2u);
  EXPECT_NEAR(double(deck[0]), shaped_at(start), 0.6);
  EXPECT_NEAR(double(deck[1]), shaped_at(end), 0.6);
  // Level across the gap, well above the bed.
  EXPECT_GT(0.5 * (double(deck[0]) + double(deck[1])), river_bed + 4.0);
  // Beyond the approaches' reach from the bridge's ends (3.5 + 2 + 15 m) and the river's from
  // its centreline 100 m along (10 + 6 + 20 m), each plus half a 10 m cell (a cell's weight is
  // its average coverage), the ground under the bridge is the DEM's, on both sides of the river.
  EXPECT_GT(expect_untouched(start, end, 26.0, 58.0), 3);
  EXPECT_GT(expect_untouched(start, end, 142.0, 174.0), 3);
}

TEST_F(OsmRun, TheTunnelLeavesTheHillUntouchedBetweenItsPortals) {
  const LineFeature tunnel = road(3002);
  ASSERT_EQ(tunnel.points.size(), 2u);
  const Vec2 west = tunnel.points.front(), east = tunnel.points.back();
  const double length = distance(west, east);
  EXPECT_NEAR(length, 720.0, 1.0);
  // Every cell along the tunnel beyond the approaches' reach of its portals (one row of 10 m
  // cells: the tunnel runs east-west 0.2 m from their centres).
  EXPECT_GE(expect_untouched(west, east, 25.0, length - 25.0), 66);
  const auto& deck = reported("roads", 3002)["deck_m"];
  EXPECT_NEAR(double(deck[0]), shaped_at(west), 0.6);
  EXPECT_NEAR(double(deck[1]), shaped_at(east), 0.6);
  // The hill stands well above the tunnel's floor.
  const double crest =
      sample_height_bilinear(original_->height, original_->grid, (west + east) * 0.5);
  EXPECT_GT(crest, 0.5 * (double(deck[0]) + double(deck[1])) + 10.0);
}

}  // namespace
}  // namespace tw
