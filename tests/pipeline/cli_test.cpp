// The terraweave command line on bad inputs (issue #2 item 11): exit code 1 and one line
// "terraweave: error: ..." naming the file, key or FID, and nothing written. Usage errors exit 2.
#include <gmock/gmock.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "synth/placements_io.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

const char* const kPipeline = R"(version: 1
seed: 1
heightfield: dem.tif
output: { dir: out, preview: false }
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 6 }
  rivers: { source: map.gpkg, layer: rivers, kind: river, width_attribute: width, width: 8,
            profile: { max_carve: 100 } }  # the line crosses bumps: no carve_limited warning
existing:
  - { source: map.gpkg, layer: existing }
)";

const VectorFeature kRoad{"LINESTRING (500100 5000100, 500300 5000300, 500500 5000350)", 6.0};
const VectorFeature kRiver{"LINESTRING (500050 5000600, 500320 5000400, 500600 5000050)", 8.0};

// Every file under a folder with its contents (outputs through their links), but terraweave's
// own .terraweave/ (where any run that locks the folder writes its pid into the lock).
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  if (!fs::exists(dir)) return files;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator();
       ++it) {
    if (it->path().filename() == ".terraweave") {
      it.disable_recursion_pending();
    } else if (it->is_regular_file()) {
      files[it->path().string()] = read_file(it->path());
    }
  }
  return files;
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    write_dem(dir / "dem.tif");
    write_layer(dir / "map.gpkg", "roads", {kRoad});
    write_layer(dir / "map.gpkg", "rivers", {kRiver});
    write_layer(dir / "map.gpkg", "existing",
                {{"POLYGON ((500400 5000500, 500450 5000500, 500450 5000550, 500400 5000550, "
                  "500400 5000500))"}});
    write_pipeline(kPipeline);
    // A previous run's outputs, which a failing run must leave exactly as they are.
    fs::create_directories(dir / "out");
    std::ofstream(dir / "out/height.exr") << "previous height";
    std::ofstream(dir / "out/notes.txt") << "kept";
  }

  void write_pipeline(const std::string& text) { std::ofstream(dir / "pipeline.yaml") << text; }

  CommandResult terraweave(const std::string& args) {
    return run_command("cd '" + dir.path().string() + "' && '" + terraweave_binary().string() +
                       "' " + args);
  }

  // Runs the pipeline with `args` and checks the failure: exit 1, one line, naming `what`,
  // and the output folder untouched.
  void expect_failure(const std::string& args, const std::vector<std::string>& what) {
    const auto before = snapshot(dir / "out");
    const CommandResult r = terraweave("-q run " + args);
    EXPECT_EQ(r.exit_code, 1) << r.output;
    std::vector<std::string> lines = lines_of(r.output);
    // Under strict the warnings that fail the run are printed first, each once.
    if (args.find("strict") != std::string::npos) {
      std::erase_if(lines, [](const std::string& l) { return l.starts_with("[warning] "); });
    }
    ASSERT_EQ(lines.size(), 1u) << r.output;
    EXPECT_THAT(lines[0], StartsWith("terraweave: error: "));
    for (const std::string& w : what) EXPECT_THAT(lines[0], HasSubstr(w));
    EXPECT_EQ(snapshot(dir / "out"), before) << "a failing run wrote into the output folder";
  }

  // Replaces the roads with `roads` in a fresh file (a Shapefile for a layer without CRS).
  void expect_bad_roads(const std::vector<VectorFeature>& roads,
                        const std::vector<std::string>& what, const std::string& crs = "EPSG:32631",
                        const std::string& extra = "") {
    const fs::path file =
        dir / ("bad" + std::to_string(++bad_files) + (crs.empty() ? ".shp" : ".gpkg"));
    write_layer(file, crs.empty() ? file.stem().string() : "roads", roads, crs);
    expect_failure("pipeline.yaml --set features.roads.source=" + file.string() +
                       (crs.empty() ? " --set features.roads.layer=" + file.stem().string() : "") +
                       extra,
                   what);
  }

  int bad_files = 0;

  TempDir dir;
};

TEST_F(Cli, GoodRunWritesEveryLayerAndKeepsOtherFiles) {
  const CommandResult r = terraweave("-q run pipeline.yaml --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* name : {"height.exr", "height.tif", "splat.exr", "splat.tif", "avoidance.exr",
                           "avoidance.tif", "report.json"}) {
    EXPECT_TRUE(fs::exists(dir / "out" / name)) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "out/preview.png"));  // output.preview: false
  EXPECT_NE(read_file(dir / "out/height.exr"), "previous height");
  EXPECT_EQ(read_file(dir / "out/notes.txt"), "kept");
  EXPECT_THAT(read_file(dir / "out/report.json"), HasSubstr("\"name\": \"rivers\""));
}

// After a good run (a folder swapped in, with .terraweave/), a failing one still changes nothing.
TEST_F(Cli, AFailingRunAfterAGoodOneLeavesItsOutputs) {
  ASSERT_EQ(terraweave("-q run pipeline.yaml").exit_code, 0);
  const std::string height = read_file(dir / "out/height.exr");
  // Fails in ingest, after the run has locked the folder.
  expect_failure("pipeline.yaml --set features.rivers.source=" + (dir / "none.gpkg").string(),
                 {"none.gpkg: file does not exist"});
  EXPECT_EQ(read_file(dir / "out/height.exr"), height);
}

TEST_F(Cli, OutAndSetOverrideThePipeline) {
  const CommandResult r =
      terraweave("-q run pipeline.yaml --out other --set output.preview=true --backend cpu");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "other/preview.png"));
  EXPECT_EQ(read_file(dir / "out/height.exr"), "previous height");
}

TEST_F(Cli, ValidateChecksInputsAndWritesNothing) {
  const auto before = snapshot(dir.path());
  CommandResult r = terraweave("validate pipeline.yaml --set output.dir=fresh");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("pipeline.yaml: ok (2 feature classes, 2 features"));
  EXPECT_EQ(snapshot(dir.path()), before);
  r = terraweave("validate pipeline.yaml --set heightfield=" + (dir / "none.tif").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("none.tif"));
}

TEST_F(Cli, MissingOrUnreadableFiles) {
  expect_failure("missing.yaml", {"missing.yaml: cannot read the pipeline file"});
  expect_failure("pipeline.yaml --set heightfield=" + (dir / "none.tif").string(),
                 {"--set heightfield=", ": heightfield: ", "none.tif: file does not exist"});
  std::ofstream(dir / "garbage.tif") << "this is not a raster";
  expect_failure("pipeline.yaml --set heightfield=" + (dir / "garbage.tif").string(),
                 {": heightfield: ", "garbage.tif: cannot be opened as raster data"});
  expect_failure("pipeline.yaml --set features.rivers.source=" + (dir / "none.gpkg").string(),
                 {": features.rivers.source: ", "none.gpkg: file does not exist"});
  expect_failure("pipeline.yaml --set features.rivers.source=" + (dir / "garbage.tif").string(),
                 {": features.rivers.source: ", "garbage.tif: cannot be opened as vector data"});
  expect_failure("pipeline.yaml --set features.rivers.layer=lakes",
                 {"error: features.rivers: ", "map.gpkg: no layer 'lakes'"});
  expect_failure("pipeline.yaml --set existing.0.layer=lakes",
                 {"error: existing.0: ", "map.gpkg: no layer 'lakes'"});
  // Named in the file: the message gives the key's line and column.
  std::string text = kPipeline;
  text.replace(text.find("heightfield: dem.tif"), 20, "heightfield: dme.tif");
  write_pipeline(text);
  expect_failure("pipeline.yaml",
                 {"pipeline.yaml:3:14: heightfield: ", "dme.tif: file does not exist"});
}

// validate opens every file a run would: a wrong exemplar path, an exemplar that is not an
// image and a NAME_height.tif twin that is not one fail at the key that names them.
TEST_F(Cli, ValidateChecksExemplarsAndTheirHeightTwins) {
  const fs::path exemplars = source_dir() / "samples/exemplars";
  fs::copy_file(exemplars / "chain_199x82.png", dir / "chain.png");
  auto pipeline_with = [&](const std::string& second) {
    std::string text = kPipeline;
    const std::string roads = "  roads: { source: map.gpkg, layer: roads, kind: road, width: 6 }\n";
    text.replace(text.find(roads), roads.size(),
                 "  roads:\n    source: map.gpkg\n    layer: roads\n    kind: road\n    width: 6\n"
                 "    synthesis: { exemplar: [chain.png, " +
                     second + "], delta: 4 }\n");
    write_pipeline(text);
  };
  auto expect_validate_failure = [&](const std::vector<std::string>& what) {
    const CommandResult r = terraweave("-q validate pipeline.yaml");
    EXPECT_EQ(r.exit_code, 1) << r.output;
    const std::vector<std::string> lines = lines_of(r.output);
    ASSERT_EQ(lines.size(), 1u) << r.output;
    for (const std::string& w : what) EXPECT_THAT(lines[0], HasSubstr(w));
  };
  pipeline_with("chian.png");
  expect_validate_failure({"pipeline.yaml:11:40: features.roads.synthesis.exemplar.1: ",
                           "chian.png: file does not exist"});
  std::ofstream(dir / "text.png") << "not an image";
  pipeline_with("text.png");
  expect_validate_failure(
      {"pipeline.yaml:11:40: features.roads.synthesis.exemplar.1: cannot be used as an exemplar",
       "text.png"});
  fs::copy_file(exemplars / "chain_199x82.png", dir / "twin.png");
  std::ofstream(dir / "twin_height.tif") << "not a raster";
  pipeline_with("twin.png");
  expect_validate_failure(
      {"pipeline.yaml:11:40: features.roads.synthesis.exemplar.1: cannot be used as an exemplar",
       "twin_height.tif"});
  pipeline_with("chain.png");
  const CommandResult ok = terraweave("-q validate pipeline.yaml");
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
}

TEST_F(Cli, UnknownKeyOrWrongTypeNamesFileLineAndColumn) {
  std::string text = kPipeline;
  text.replace(text.find("width: 6"), 5, "widht");
  write_pipeline(text);
  expect_failure("pipeline.yaml",
                 {"pipeline.yaml:6:56: features.roads.widht: unknown key (did you mean 'width'?)"});
  text = kPipeline;
  text.replace(text.find("width: 6"), 8, "width: six");
  write_pipeline(text);
  expect_failure("pipeline.yaml",
                 {"pipeline.yaml:6:63: features.roads.width: expected a number, got 'six'"});
  write_pipeline(kPipeline);
  expect_failure("pipeline.yaml --set features.roads.colour=red",
                 {"--set features.roads.colour=red: features.roads.colour: unknown key"});
}

TEST_F(Cli, MissingOrIncompatibleCrs) {
  DemSpec no_crs;
  no_crs.crs = "";
  write_dem(dir / "nocrs.tif", no_crs);
  expect_failure("pipeline.yaml --set heightfield=" + (dir / "nocrs.tif").string(),
                 {"nocrs.tif: has no CRS"});
  expect_bad_roads({kRoad}, {"bad1.shp:bad1: layer has no CRS"}, "");
  // The same numbers in a UTM zone of the other hemisphere land thousands of km away.
  expect_bad_roads({kRoad},
                   {"strict: 1 warning", "bad2.gpkg:roads", "no line feature on the heightfield"},
                   "EPSG:31985", " --strict");
}

// A class with nothing on the heightfield is a warning: the run succeeds and lists it;
// --strict (or `strict: true`) makes it fail and write nothing.
TEST_F(Cli, EmptyClassIsAWarningUnlessStrict) {
  expect_bad_roads({},
                   {"strict: 1 warning",
                    "features.roads: ", "bad1.gpkg:roads: no line feature on the heightfield"},
                   "EPSG:32631", " --strict");
  expect_failure("pipeline.yaml --strict --set \"features.rivers.where=width > 100\"",
                 {"features.rivers:", "no line feature"});
  expect_failure("pipeline.yaml --set strict=true --set \"features.rivers.where=width > 100\"",
                 {"features.rivers:", "no line feature"});

  const CommandResult r =
      terraweave("-q run pipeline.yaml --set \"features.rivers.where=width > 100\"");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("[warning] features.rivers: "));
  const nlohmann::json report = nlohmann::json::parse(read_file(dir / "out/report.json"));
  EXPECT_EQ(report["warning_count"], 1);
  ASSERT_EQ(report["warnings"].size(), 1u);
  EXPECT_EQ(report["warnings"][0]["code"], "empty_class");
  EXPECT_EQ(report["warnings"][0]["subject"], "features.rivers");
  EXPECT_FALSE(report["warnings"][0].contains("fid"));
  ASSERT_EQ(report["classes"].size(), 2u);
  EXPECT_EQ(report["classes"][1]["features"].size(), 0u);
  EXPECT_EQ(report["classes"][0]["features"].size(), 1u);

  const CommandResult v =
      terraweave("validate pipeline.yaml --set \"features.rivers.where=width > 100\"");
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_THAT(v.output, HasSubstr("1 warnings"));
  const CommandResult vs =
      terraweave("-q validate --strict pipeline.yaml --set \"features.rivers.where=width > 100\"");
  EXPECT_EQ(vs.exit_code, 1) << vs.output;
}

TEST_F(Cli, PointsOrPolygonsWhereLinesAreExpected) {
  expect_bad_roads({kRoad, {"POINT (500100 5000100)", 5.0}},
                   {"error: features.roads: ", "bad1.gpkg:roads: FID 2: is a Point where lines"});
  expect_bad_roads(
      {{"POLYGON ((500100 5000100, 500200 5000100, 500200 5000200, 500100 5000100))", 5.0}},
      {"bad2.gpkg:roads: FID 1: is a Polygon where lines"});
}

// Messy lines are repaired with a warning naming the FID, a road crossing itself (a loop ramp)
// runs as drawn, and --strict turns the repair into a failure that writes nothing.
TEST_F(Cli, MessyLinesAreRepairedAndSelfCrossingRoadsRun) {
  const fs::path roads = dir / "messy.gpkg";
  write_layer(roads, "roads",
              {{"LINESTRING (500100 5000100, 500100 5000100)", 5.0},
               {"LINESTRING (500100 5000100, 500300 5000300, 500300 5000100, 500100 5000300)", 5.0},
               {"LINESTRING (500100 5000500, 500300 5000500, 500300 5000520, 500300.3 5000500, "
                "500500 5000500)",
                5.0}});
  const std::string args = "pipeline.yaml --set features.roads.source=" + roads.string();
  const CommandResult r = terraweave("-q run " + args);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json report = nlohmann::json::parse(read_file(dir / "out/report.json"));
  ASSERT_EQ(report["warning_count"], 2) << report["warnings"].dump();
  for (const auto& [i, fid, says] : {std::tuple{0, 1, "1 duplicate vertex and 1 zero-length part"},
                                     std::tuple{1, 3, "removed 1 spike"}}) {
    const nlohmann::json& w = report["warnings"][i];
    EXPECT_EQ(w["code"], "repaired");
    EXPECT_EQ(w["subject"], "features.roads");
    EXPECT_EQ(w["fid"], fid);
    EXPECT_THAT(w["message"].get<std::string>(), HasSubstr(says));
  }
  std::vector<std::int64_t> fids;
  for (const auto& c : report["classes"])
    if (c["name"] == "roads")
      for (const auto& f : c["features"]) fids.push_back(f["fid"]);
  EXPECT_EQ(fids, (std::vector<std::int64_t>{2, 3}));
  expect_failure("--strict " + args, {"strict: 2 warnings", "features.roads: FID 1"});
}

TEST_F(Cli, NanOrHugeCoordinates) {
  expect_bad_roads({{"LINESTRING (500100 5000100, 1e300 5000300)", 5.0}},
                   {"error: features.roads: ", "bad1.gpkg:roads: FID 1",
                    "non-finite or out-of-range coordinate"});
  expect_bad_roads({VectorFeature({{500100, 5000100}, {std::nan(""), 5000300}}, 5.0)},
                   {"bad2.gpkg:roads: FID 1", "non-finite or out-of-range coordinate"});
}

TEST_F(Cli, DemAllNodata) {
  DemSpec empty;
  empty.nodata = -9999.0;
  empty.all_nodata = true;
  write_dem(dir / "empty.tif", empty);
  expect_failure("pipeline.yaml --set heightfield=" + (dir / "empty.tif").string(),
                 {"empty.tif: every cell is nodata"});
}

TEST_F(Cli, WidthNotPositive) {
  expect_failure("pipeline.yaml --set features.roads.width=0",
                 {"--set features.roads.width=0: features.roads.width: must be > 0, got 0"});
  write_layer(dir / "bad.gpkg", "rivers",
              {kRiver, {"LINESTRING (500100 5000500, 500200 5000450)", -3.0}});
  expect_failure("pipeline.yaml --set features.rivers.source=" + (dir / "bad.gpkg").string(),
                 {"bad.gpkg:rivers: FID 2: width must be a positive number of metres, got -3"});
}

TEST_F(Cli, SynthDrawsOneRibbonOrNamesTheBadInput) {
  const std::string exemplar = (source_dir() / "samples/exemplars/chain_199x82.png").string();
  CommandResult r = terraweave("-q synth --exemplar " + exemplar +
                               " --curve line --length 12 --width 4 --delta 3 --scale 4 "
                               "--backend cpu -o synth.png");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("4 pieces, Omega "));
  EXPECT_GT(fs::file_size(dir / "synth.png"), 0u);
  // The placements file loads back with the same pieces and cost.
  r = terraweave("-q synth --exemplar " + exemplar +
                 " --curve line --length 12 --width 4 --delta 3 --scale 4 --min-coverage 0.2 "
                 "--no-stitch --backend cpu -o synth2.png --placements synth2.json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::string exemplar_in_file;
  const Synthesis back = load_placements((dir / "synth2.json").string(), &exemplar_in_file);
  EXPECT_EQ(back.placements.size(), 4u);
  EXPECT_EQ(exemplar_in_file, exemplar);
  EXPECT_THAT(r.output, HasSubstr("Omega " + std::to_string(back.total_cost) + ","));
  EXPECT_EQ(back.mean_seam_cost_stitched, back.mean_seam_cost);  // --no-stitch
  // Continuous alpha prices the chain's soft edges too: another optimum cost.
  const std::string arc = " --curve arc --length 12 --width 4 --delta 3 --scale 4 --backend cpu";
  const CommandResult binary = terraweave("-q synth --exemplar " + exemplar + arc + " -o b.png");
  const CommandResult continuous =
      terraweave("-q synth --exemplar " + exemplar + arc + " --alpha continuous -o c.png");
  ASSERT_EQ(binary.exit_code, 0) << binary.output;
  ASSERT_EQ(continuous.exit_code, 0) << continuous.output;
  EXPECT_NE(binary.output, continuous.output);
  EXPECT_EQ(
      terraweave("-q synth --exemplar " + exemplar + arc + " --alpha soft -o d.png").exit_code, 2);
  r = terraweave(
      "-q synth --exemplar " + exemplar +
      " --curve line --length 12 --width 4 --delta 3 --scale 4 --min-coverage 1 -o y.png");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("min_coverage must be in [0, 1)"));
  EXPECT_FALSE(fs::exists(dir / "y.png"));
  r = terraweave(
      "-q synth --exemplar none.png --curve line --width 4 --delta 3 --scale 4 -o x.png");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(lines_of(r.output), ::testing::ElementsAre(StartsWith("terraweave: error: ")));
  EXPECT_THAT(r.output, HasSubstr("none.png"));
  r = terraweave("-q synth --exemplar " + exemplar +
                 " --curve map.gpkg:nolayer --width 4 --delta 3 --scale 4 -o x.png");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("map.gpkg: no layer 'nolayer'"));
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

TEST_F(Cli, ExemplarInspectAndSynthDefaultsFromTheExemplar) {
  const std::string ridge = (source_dir() / "samples/exemplars/ridge_band_200x64.png").string();
  CommandResult r = terraweave("-q exemplar inspect " + ridge + " --json --preview p.png");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["width"], 200);
  EXPECT_EQ(j["height"], 64);
  // The band holds the ridge, not the two stray texels above it.
  const int top = j["band_rows"][0], bottom = j["band_rows"][1];
  EXPECT_GT(top, 5);
  EXPECT_LT(bottom, 60);
  EXPECT_GT(j["natural_coverage"].get<double>(), 0.5);
  EXPECT_GT(j["suggested_delta"].get<int>(), 3);
  EXPECT_EQ(j["column_coverage"]["values"].size(), 200u);
  // The preview: the exemplar plus a 24-row coverage strip.
  const auto preview = OIIO::ImageInput::open((dir / "p.png").string());
  ASSERT_TRUE(preview);
  EXPECT_EQ(preview->spec().width, 200);
  EXPECT_EQ(preview->spec().height, 64 + 24);
  r = terraweave("-q exemplar inspect " + ridge);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("opaque rows   " + std::to_string(top) + ".." +
                                  std::to_string(bottom)));
  EXPECT_EQ(terraweave("-q exemplar inspect missing.png").exit_code, 1);
  // synth without --width and --delta: both from the exemplar.
  r = terraweave("-q synth --exemplar " + ridge +
                 " --curve s-curve --length 200 --scale 1 --backend cpu -o s.png");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("pieces, Omega "));
}

TEST_F(Cli, UsageErrorsExitWithTwo) {
  EXPECT_EQ(terraweave("run").exit_code, 2);
  EXPECT_EQ(terraweave("frobnicate pipeline.yaml").exit_code, 2);
  EXPECT_EQ(terraweave("run pipeline.yaml --threads 0").exit_code, 2);
  EXPECT_EQ(terraweave("run pipeline.yaml --backend gpu").exit_code, 2);
  EXPECT_EQ(snapshot(dir / "out").size(), 2u);
}

TEST_F(Cli, SubcommandHelpListsTheGlobalOptions) {
  for (const char* sub : {"run", "grow", "export", "view", "render-tile"}) {
    const CommandResult r = terraweave(std::string(sub) + " --help");
    EXPECT_EQ(r.exit_code, 0) << sub;
    EXPECT_THAT(r.output, HasSubstr("Global options (before or after the subcommand):")) << sub;
    for (const char* global : {"--verbose", "--quiet", "--threads", "--strict", "--allow-network"})
      EXPECT_THAT(r.output, HasSubstr(global)) << sub << " --help lacks " << global;
  }
  // The run's own options are still there.
  EXPECT_THAT(terraweave("run --help").output, HasSubstr("--backend"));
}

// Issue #24: NaN and infinities are refused by every number option before anything runs.
TEST_F(Cli, NonFiniteNumbersAreRefusedByEveryNumberOption) {
  for (const char* args :
       {"area sketch.geojson --polygons map.gpkg:existing --bearing nan",
        "grow --dem dem.tif --region 0,0,1,1 --resolution nan",
        "grow --dem dem.tif --region 0,0,1,1 --resolution inf",
        "synth --exemplar e.png --scale 1e400 -o o.png",
        "network synthesize --exemplar e.gpkg --region 0,0,1,1 --lead-bearing nan "
        "--out o",
        "network clone --map m.gpkg --source-region s.gpkg --target-region t.gpkg "
        "--clearance inf --out o"}) {
    const CommandResult r = terraweave(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr("is not a finite number")) << args;
  }
}

TEST_F(Cli, VersionNamesTheLibraries) {
  const CommandResult r = terraweave("--version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("terraweave 0.1.0 (GDAL"));
}

}  // namespace
}  // namespace tw::test
