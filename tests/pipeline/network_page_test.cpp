// Issue #20 item 4 (docs/networks.md, "Drawing"): the drawing page of `terraweave view RUN
// --serve 0 --exemplar ...` driven in headless Chromium by real pointer input
// (network_page_drive.py, over the DevTools protocol): a stroke is drawn, a region dragged,
// completed, suggestions accepted one by a click and others by a lasso, the rest rejected,
// completed again, all accepted, that undone (Ctrl+Z) and redone, saved. The GeoPackage holds the
// stroke exactly as the page drew it (within a pixel of where the pointer went) and the accepted
// suggestions, in the run's CRS, off the run's road; a pipeline reads it as a line class; the
// reloaded page shows it again bit for bit; strokes starting 2 px from a line or from its end
// start exactly on it, and undo removes them; the server is gone afterwards.
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>
#include <signal.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "test_support.hpp"
#include "test_world.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;

const char* const kNetworkPagePipeline = R"(version: 1
seed: 3
generate: { width: 64, height: 48, pixel_size: 10, relief: 60, origin: [500000, 5000000] }
output: { dir: out, preview: false, exr: false }
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 12 }
)";
const char* const kRoad = "LINESTRING (500050 4999600, 500300 4999800, 500600 4999700)";

// Each test's run: the generated world with its road (kRoad), run in a temporary folder; `cd`
// and `binary` start a shell command there; `svg`: the drawn exemplar.
class NetworkPage : public ::testing::Test {
 protected:
  void SetUp() override {
    write_layer(dir / "map.gpkg", "roads", {{kRoad, 12.0}});
    std::ofstream(dir / "pipeline.yaml") << kNetworkPagePipeline;
    const CommandResult run = run_command(cd + binary + " -q run pipeline.yaml 2>&1");
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  TempDir dir;
  const std::string cd = "cd '" + dir.path().string() + "' && ";
  const std::string binary = "'" + terraweave_binary().string() + "'";
  const std::string svg = (source_dir() / "tests/data/network_drawn.svg").string();
};

TEST_F(NetworkPage, DrawCompleteAcceptAndSaveInHeadlessChromium) {
  const CommandResult drive =
      run_command(cd + "timeout 120 /usr/bin/python3 '" +
                  (source_dir() / "tests/pipeline/network_page_drive.py").string() + "' " + binary +
                  " out . --exemplar '" + svg +
                  "' --scale 0.5 --report report.json --screenshot shot.png 2>&1");
  ASSERT_EQ(drive.exit_code, 0) << drive.output;
  const nlohmann::json r = nlohmann::json::parse(read_file(dir / "report.json"));

  // The loop as the user saw it.
  EXPECT_GE(r["first_suggestions"].get<int>(), 3);
  EXPECT_EQ(r["after_click"], 2);  // the stroke and the suggestion clicked
  EXPECT_GT(r["after_lasso"].get<int>(), 2);
  EXPECT_GT(r["left_after_lasso"].get<int>(), 0);  // the lasso took only some
  EXPECT_EQ(r["after_reject"], 0);
  EXPECT_EQ(r["second_region_points"], 8);  // the second region: a loop, not a box
  EXPECT_GT(r["second_suggestions"].get<int>(), 0) << r["second_status"];
  // The status line names the method that completed the drawing: automatic (the page's default)
  // grows from the drawn ends.
  EXPECT_EQ(r["first_status"], std::to_string(r["first_suggestions"].get<int>()) +
                                   " suggestions, completed by growth (automatic chose it)");
  // The second completion was turned to a bearing typed in the box the lead `bearing` shows.
  EXPECT_EQ(r["bearing_box"], nlohmann::json::parse("[true, true]"));
  EXPECT_EQ(r["bar_fits"], true);  // in a 1000-pixel window, the bearing box shown
  EXPECT_EQ(r["second_status"], std::to_string(r["second_suggestions"].get<int>()) +
                                    " suggestions, completed by growth (automatic chose it), "
                                    "turned to 45.0°");
  const auto& lines = r["lines"];
  ASSERT_EQ(lines.size(), r["after_lasso"].get<std::size_t>() + r["second_suggestions"].get<int>());
  EXPECT_TRUE(fs::equivalent(r["saved"].get<std::string>(), dir / "drawn_network.gpkg"));
  EXPECT_EQ(r["view_page"], true);  // the 3D page, served from the run's page folder
  // The server was stopped with the test's driver.
  EXPECT_EQ(kill(r["server_pid"].get<int>(), 0), -1);
  EXPECT_EQ(errno, ESRCH);

  // Ctrl+Z took "accept all" back (its lines were suggestions again), then all were accepted.
  EXPECT_EQ(r["after_undo_accept"][0], r["after_lasso"]);
  EXPECT_EQ(r["after_undo_accept"][1], r["second_suggestions"]);
  EXPECT_EQ(r["all_accepted"].get<std::size_t>(), lines.size());

  // Reloaded, the page shows the saved drawing again: every line bit for bit, with its origin.
  EXPECT_EQ(r["reloaded"]["lines"], lines);
  EXPECT_EQ(r["reloaded"]["origins"], r["origins"]);
  // A stroke starting 2 px from the middle of a segment of the first line starts on it: that
  // point is inserted into the first line, so both hold the same doubles (a T-junction).
  const auto& on_segment = r["on_segment"]["lines"];
  ASSERT_EQ(on_segment.size(), lines.size() + 1);
  const nlohmann::json joined = on_segment.back().front();
  ASSERT_EQ(on_segment[0].size(), lines[0].size() + 1);
  EXPECT_EQ(std::count(on_segment[0].begin(), on_segment[0].end(), joined), 1);
  const auto pixels_between = [&](const nlohmann::json& a, const nlohmann::json& b) {
    return std::hypot((a[0].get<double>() - b[0].get<double>()) / r["pixel"][0].get<double>(),
                      (a[1].get<double>() - b[1].get<double>()) / r["pixel"][1].get<double>());
  };
  EXPECT_NEAR(pixels_between(joined, r["segment_stroke_dispatched"]), 2.0, 1.0);
  // The undo button removes the stroke and the vertex it added.
  EXPECT_EQ(r["after_undo_button"]["lines"], lines);
  // A stroke starting 2 px beyond the first line's end starts exactly at that end.
  const auto& at_end = r["at_end"]["lines"];
  ASSERT_EQ(at_end.size(), lines.size() + 1);
  EXPECT_EQ(at_end.back().front(), lines[0].back());
  EXPECT_NEAR(pixels_between(lines[0].back(), r["end_stroke_dispatched"]), 2.0, 1.0);
  EXPECT_EQ(at_end[0], lines[0]);
  // Ctrl+Z removes it; with nothing left to undo the saved lines stay.
  EXPECT_EQ(r["after_ctrl_z"]["lines"], lines);
  EXPECT_EQ(r["after_nothing_to_undo"]["lines"], lines);
  EXPECT_EQ(r["undo_status"], "nothing to undo");

  // The stroke is where the pointer went (within a pixel of the page's map).
  const auto& stroke = lines[0];
  const auto& dispatched = r["dispatched_map"];
  ASSERT_EQ(stroke.size(), dispatched.size());
  const double pixel = std::max(r["pixel"][0].get<double>(), r["pixel"][1].get<double>());
  for (std::size_t i = 0; i < stroke.size(); ++i)
    for (int c = 0; c < 2; ++c)
      EXPECT_NEAR(stroke[i][c].get<double>(), dispatched[i][c].get<double>(), pixel);

  // The GeoPackage: every line as the page held it, bit for bit, in the run's CRS.
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(
      GDALDataset::Open((dir / "drawn_network.gpkg").c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  ASSERT_TRUE(ds);
  OGRLayer* layer = ds->GetLayerByName("lines");
  ASSERT_TRUE(layer);
  ASSERT_TRUE(layer->GetSpatialRef());
  OGRSpatialReference utm;
  utm.importFromEPSG(32631);
  EXPECT_TRUE(layer->GetSpatialRef()->IsSame(&utm));
  ASSERT_EQ(layer->GetFeatureCount(), GIntBig(lines.size()));
  std::unique_ptr<OGRGeometry> road;
  {
    OGRGeometry* g = nullptr;
    OGRGeometryFactory::createFromWkt(kRoad, nullptr, &g);
    road.reset(g);
  }
  std::size_t i = 0;
  for (auto& f : *layer) {
    EXPECT_STREQ(f->GetFieldAsString("origin"), i == 0 ? "drawn" : "suggested");
    const OGRLineString* ls = f->GetGeometryRef()->toLineString();
    ASSERT_EQ(std::size_t(ls->getNumPoints()), lines[i].size()) << "line " << i + 1;
    for (int k = 0; k < ls->getNumPoints(); ++k) {
      EXPECT_EQ(ls->getX(k), lines[i][k][0].get<double>()) << "line " << i + 1;
      EXPECT_EQ(ls->getY(k), lines[i][k][1].get<double>()) << "line " << i + 1;
    }
    if (i > 0) {
      EXPECT_FALSE(ls->Intersects(road.get())) << "suggestion " << i + 1;
    }
    ++i;
  }

  // A pipeline reads it: the lines become a line class of the run.
  std::ofstream(dir / "pipeline.yaml", std::ios::app)
      << "  drawn: { source: drawn_network.gpkg, layer: lines, kind: road, width: 3 }\n";
  const CommandResult again =
      run_command(cd + binary + " -q run pipeline.yaml --set output.dir=again 2>&1");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  const nlohmann::json features = nlohmann::json::parse(read_file(dir / "again/features.geojson"));
  std::set<int> drawn;  // FIDs of the class's features
  for (const auto& f : features["features"])
    if (f["properties"]["class"] == "drawn") drawn.insert(f["properties"]["fid"].get<int>());
  EXPECT_EQ(drawn.size(), lines.size());
  EXPECT_TRUE(drawn.count(1));  // the stroke

  // The screenshot (docs/images/network_draw.png is one) shows suggestions in green.
  EXPECT_GT(fs::file_size(dir / "shot.png"), 10000u);
}

// The drawing page's server options (`view --serve --exemplar SRC --where --scale --seed --save`)
// and its method choice act in its answers: one stroke completed in one region against servers
// started with each option changed (view_drawing_requests.py, plain HTTP), the suggestions or
// the saved file differ.
// The option tables (option_tables_test.cpp) point here for these rows.
TEST_F(NetworkPage, EveryDrawingOptionChangesWhatTheServerAnswersOrWrites) {
  // An exemplar with two kinds of lines, for --where: a field grid ('a') and diagonals ('b').
  std::vector<VectorFeature> lines;
  for (int i = 0; i <= 4; ++i) {
    const std::string x = std::to_string(i * 150), y = std::to_string(i * 100);
    lines.push_back({"LINESTRING (" + x + " 0, " + x + " 400)", 1.0, {{"kind", "a"}}});
    lines.push_back({"LINESTRING (0 " + y + ", 600 " + y + ")", 1.0, {{"kind", "a"}}});
  }
  lines.push_back({"LINESTRING (0 0, 150 100)", 1.0, {{"kind", "b"}}});
  lines.push_back({"LINESTRING (300 100, 450 300)", 1.0, {{"kind", "b"}}});
  write_layer(dir / "exemplar.gpkg", "lines", lines);

  // The stroke inside the region. `methods`: the completions asked of one server, by the
  // request's `method` as the page's method choice sets it ("-": none named).
  const std::string stroke_region =
      "'[[500080, 4999900], [500200, 4999930]]' "
      "'[[500040, 4999850], [500620, 4999850], [500620, 4999990], [500040, 4999990]]' ";
  const auto request = [&](const std::string& options, const std::string& methods = "",
                           const std::string& stroke_and_region = "") {
    return run_command(cd + (methods.empty() ? "" : "COMPLETE_METHOD=" + methods + " ") +
                       "timeout 120 /usr/bin/python3 '" +
                       (source_dir() / "tests/pipeline/view_drawing_requests.py").string() + "' " +
                       binary + " out . " +
                       (stroke_and_region.empty() ? stroke_region : stroke_and_region) + options);
  };
  const auto ask = [&](const std::string& options) {
    const CommandResult r = request(options);
    EXPECT_EQ(r.exit_code, 0) << options << ": " << r.output;
    const nlohmann::json answer = nlohmann::json::parse(r.output, nullptr, false);
    EXPECT_FALSE(answer.is_discarded()) << r.output;
    std::printf("%-60s %zu suggestions\n", options.c_str(),
                answer.is_discarded() ? 0 : answer["suggestions"].size());
    return answer;
  };
  const std::string base = "--exemplar '" + svg + "' --scale 0.5 --seed 1 --save a.gpkg";
  const nlohmann::json a = ask(base);
  ASSERT_FALSE(a.is_discarded());
  ASSERT_GT(a["suggestions"].size(), 0u);
  EXPECT_TRUE(fs::equivalent(a["saved"].get<std::string>(), dir / "a.gpkg"));
  EXPECT_EQ(a["drawing"]["status"], 200);
  EXPECT_EQ(a["drawing"]["body"]["lines"], nlohmann::json::array());  // nothing saved yet
  const std::string gpkg = "--exemplar exemplar.gpkg --seed 1 --save a.gpkg";
  const nlohmann::json all_kinds = ask(gpkg);
  // The next server serves back what the first saved, the same doubles, with their origins.
  ASSERT_EQ(all_kinds["drawing"]["status"], 200);
  const nlohmann::json& reloaded = all_kinds["drawing"]["body"];
  ASSERT_EQ(reloaded["lines"].size(), a["suggestions"].size() + 1);
  EXPECT_EQ(reloaded["lines"][0], nlohmann::json::parse("[[500080, 4999900], [500200, 4999930]]"));
  for (std::size_t i = 0; i < a["suggestions"].size(); ++i)
    EXPECT_EQ(reloaded["lines"][i + 1], a["suggestions"][i]) << i;
  EXPECT_EQ(reloaded["origins"][0], "drawn");
  EXPECT_EQ(reloaded["origins"][1], "suggested");
  const nlohmann::json grid_only = ask(gpkg + " --where \"kind = 'a'\"");
  EXPECT_NE(all_kinds["suggestions"], a["suggestions"]) << "--exemplar";
  EXPECT_NE(grid_only["suggestions"], all_kinds["suggestions"]) << "--where";
  EXPECT_NE(ask("--exemplar '" + svg + "' --scale 0.8 --seed 1 --save a.gpkg")["suggestions"],
            a["suggestions"])
      << "--scale";
  EXPECT_NE(ask("--exemplar '" + svg + "' --scale 0.5 --seed 2 --save a.gpkg")["suggestions"],
            a["suggestions"])
      << "--seed";
  const nlohmann::json saved_b =
      ask("--exemplar '" + svg + "' --scale 0.5 --seed 1 --save sub_b.gpkg");
  EXPECT_EQ(saved_b["suggestions"], a["suggestions"]) << "--save: where, not what";
  EXPECT_TRUE(fs::equivalent(saved_b["saved"].get<std::string>(), dir / "sub_b.gpkg")) << "--save";
  // The page's method choice: over a region without drawn lines (south of the stroke, clear of
  // the road) growth, quilting and the layout answer differently, and naming none is automatic
  // (which chooses among them). Quilting or laying out a region with drawn lines is refused
  // (completing is growth from their ends), as is a method of another name.
  const std::string empty_south =
      "'[[500080, 4999900], [500200, 4999930]]' "
      "'[[500300, 4999530], [500620, 4999530], [500620, 4999660], [500300, 4999660]]' ";
  const std::string plain = "--exemplar '" + svg + "' --scale 0.5 --seed 1 --save m.gpkg";
  const auto completions = [&](const std::string& methods, const std::string& stroke_and_region) {
    const CommandResult r = request(plain, methods, stroke_and_region);
    EXPECT_EQ(r.exit_code, 0) << methods << ": " << r.output;
    const nlohmann::json answer = nlohmann::json::parse(r.output, nullptr, false);
    EXPECT_FALSE(answer.is_discarded()) << r.output;
    return answer.is_discarded() ? nlohmann::json::object() : answer["completions"];
  };
  const nlohmann::json south = completions("growth,quilt,layout,automatic,-", empty_south);
  for (const char* method : {"growth", "quilt", "layout", "automatic", "-"})
    ASSERT_EQ(south[method]["status"], 200) << method;
  const nlohmann::json& grown = south["growth"]["body"]["suggestions"];
  const nlohmann::json& quilted = south["quilt"]["body"]["suggestions"];
  const nlohmann::json& laid_out = south["layout"]["body"]["suggestions"];
  const nlohmann::json& chosen = south["-"]["body"]["suggestions"];
  std::printf("method growth %zu, quilt %zu, layout %zu, none named %zu suggestions\n",
              grown.size(), quilted.size(), laid_out.size(), chosen.size());
  ASSERT_GT(grown.size(), 0u);
  ASSERT_GT(quilted.size(), 0u);
  ASSERT_GT(laid_out.size(), 0u);
  EXPECT_NE(grown, quilted) << "method";
  EXPECT_NE(grown, laid_out) << "method";
  EXPECT_EQ(chosen, south["automatic"]["body"]["suggestions"]) << "no method: automatic";
  EXPECT_GT(chosen.size(), 0u) << "automatic";
  // Each answer names the method asked and the one that made its suggestions (the page's status
  // line shows both): a method named makes them itself; automatic picks one of the three, and
  // its suggestions are that method's own.
  for (const char* method : {"growth", "quilt", "layout"}) {
    EXPECT_EQ(south[method]["body"]["method"], method);
    EXPECT_EQ(south[method]["body"]["chosen"], method);
  }
  for (const char* unnamed : {"automatic", "-"}) {
    EXPECT_EQ(south[unnamed]["body"]["method"], "automatic") << unnamed;
    const nlohmann::json& automatic_chose = south[unnamed]["body"]["chosen"];
    ASSERT_TRUE(automatic_chose == "growth" || automatic_chose == "quilt" ||
                automatic_chose == "layout")
        << automatic_chose;
    EXPECT_EQ(chosen, south[automatic_chose.get<std::string>()]["body"]["suggestions"])
        << "automatic chose " << automatic_chose;
  }
  const nlohmann::json over_stroke = completions("quilt,layout,grow", stroke_region);
  for (const char* method : {"quilt", "layout"}) {
    EXPECT_EQ(over_stroke[method]["status"], 400) << method;
    EXPECT_THAT(over_stroke[method]["body"]["error"].get<std::string>(),
                ::testing::HasSubstr("method " + std::string(method) +
                                     " cannot complete a drawing (the region holds drawn lines)"));
  }
  EXPECT_EQ(over_stroke["grow"]["status"], 400);
  EXPECT_EQ(over_stroke["grow"]["body"]["error"],
            "key method: \"grow\" is none of automatic, growth, quilt, layout");

  // A drawing in another CRS than the run's is not shown: the page says why.
  write_layer(dir / "lon_lat.gpkg", "lines", {{"LINESTRING (3 45, 3.1 45.1)"}}, "EPSG:4326");
  const nlohmann::json other_crs =
      ask("--exemplar '" + svg + "' --scale 0.5 --seed 1 --save lon_lat.gpkg");
  EXPECT_EQ(other_crs["drawing"]["status"], 400);
  EXPECT_THAT(other_crs["drawing"]["body"]["error"].get<std::string>(),
              ::testing::HasSubstr("lon_lat.gpkg: the drawing is not in the run's CRS"));
}

// The page's lead choice (docs/networks.md, "Drawing", lead): over a region clear of the stroke,
// each lead turns the completion to the bearing it answers, which is the pipeline's own reading
// of that lead there (the long axis of a wide box: 90°; the run's road segment nearest to the
// box: 108.4° modulo 180°), and its suggestions are those of that bearing given as
// {"bearing": DEG}; without a lead none is named. A run without a road says so and follows the
// long axis; unknown leads and bearings that are no angle are refused naming the key.
TEST_F(NetworkPage, TheLeadTurnsTheCompletionAsAPipelinesLeadDoes) {
  // South of the stroke, clear of the road: 320 m wide, 130 m tall.
  const std::string stroke_and_region =
      "'[[500080, 4999900], [500200, 4999930]]' "
      "'[[500300, 4999530], [500620, 4999530], [500620, 4999660], [500300, 4999660]]' ";
  const auto completions = [&](const std::string& run_dir, const nlohmann::json& leads) {
    const CommandResult r =
        run_command(cd + "COMPLETE_LEADS='" + leads.dump() + "' timeout 120 /usr/bin/python3 '" +
                    (source_dir() / "tests/pipeline/view_drawing_requests.py").string() + "' " +
                    binary + " " + run_dir + " . " + stroke_and_region + "--exemplar '" + svg +
                    "' --scale 0.5 --seed 1 --save lead.gpkg");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json answer = nlohmann::json::parse(r.output, nullptr, false);
    EXPECT_FALSE(answer.is_discarded()) << r.output;
    return answer.is_discarded() ? nlohmann::json::array() : answer["completions"];
  };
  const nlohmann::json leads = nlohmann::json::parse(
      R"([null, "long_axis", "nearest_road", "contours", {"bearing": 30}, "uphill",
          {"bearing": "east"}])");
  const nlohmann::json asked = completions("out", leads);
  ASSERT_EQ(asked.size(), leads.size());
  for (std::size_t i = 0; i < 5; ++i) {
    ASSERT_EQ(asked[i]["status"], 200) << leads[i];
    EXPECT_GT(asked[i]["body"]["suggestions"].size(), 0u) << leads[i];
    EXPECT_FALSE(asked[i]["body"].contains("warning")) << leads[i];
  }
  EXPECT_TRUE(asked[0]["body"]["lead_bearing_deg"].is_null());
  const double long_axis = asked[1]["body"]["lead_bearing_deg"].get<double>();
  const double nearest_road = asked[2]["body"]["lead_bearing_deg"].get<double>();
  const double contours = asked[3]["body"]["lead_bearing_deg"].get<double>();
  EXPECT_NEAR(std::fmod(long_axis, 180.0), 90.0, 1e-6);
  // The road's segment from (500300, 4999800) to (500600, 4999700): 3 east for 1 south.
  EXPECT_NEAR(std::fmod(nearest_road, 180.0), 90.0 + std::atan(1.0 / 3.0) * 180.0 / M_PI, 1e-6);
  EXPECT_GE(contours, 0.0);
  EXPECT_LT(contours, 360.0);
  EXPECT_EQ(asked[4]["body"]["lead_bearing_deg"], 30.0);
  for (std::size_t i = 1; i < 5; ++i)
    EXPECT_NE(asked[i]["body"]["suggestions"], asked[0]["body"]["suggestions"]) << leads[i];
  // Each lead's suggestions are its bearing's (the same doubles sent back).
  const nlohmann::json as_bearings = completions(
      "out", {{{"bearing", long_axis}}, {{"bearing", nearest_road}}, {{"bearing", contours}}});
  ASSERT_EQ(as_bearings.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    ASSERT_EQ(as_bearings[i]["status"], 200) << i;
    EXPECT_EQ(as_bearings[i]["body"]["suggestions"], asked[i + 1]["body"]["suggestions"])
        << leads[i + 1];
  }
  EXPECT_EQ(asked[5]["status"], 400);
  EXPECT_EQ(asked[5]["body"]["error"],
            "key lead: \"uphill\" is none of long_axis, nearest_road, contours or "
            "{\"bearing\": DEG}");
  EXPECT_EQ(asked[6]["status"], 400);
  EXPECT_EQ(asked[6]["body"]["error"],
            "key lead.bearing: \"east\" is not a finite angle in degrees");

  // A run without a road (the same line as a river): the nearest road falls back to the long
  // axis, and says so.
  std::string bare = kNetworkPagePipeline;
  bare.replace(bare.find("kind: road"), 10, "kind: river");
  std::ofstream(dir / "bare.yaml") << bare;
  const CommandResult bare_run =
      run_command(cd + binary + " -q run bare.yaml --set output.dir=bare 2>&1");
  ASSERT_EQ(bare_run.exit_code, 0) << bare_run.output;
  const nlohmann::json roadless = completions("bare", {"nearest_road"});
  ASSERT_EQ(roadless.size(), 1u);
  ASSERT_EQ(roadless[0]["status"], 200);
  EXPECT_NEAR(std::fmod(roadless[0]["body"]["lead_bearing_deg"].get<double>(), 180.0), 90.0, 1e-6);
  EXPECT_EQ(roadless[0]["body"]["warning"],
            "no road in the run: the lines follow the region's long axis");
}

}  // namespace
}  // namespace tw::test
