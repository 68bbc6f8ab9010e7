// The plan as a folder (pipeline/plan_io.hpp), the run in three steps (pipeline/job.hpp) and the
// syntheses as tasks (pipeline/synthesis_job.hpp) on
// a small world with everything a plan holds: a DEM, three roads (one a ring) with synthesized
// cobble patterns (colour, alpha and height channels), junctions, 3 x 3 tiles.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/content_hash.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "pipeline/detail/job_files.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/plan_objects.hpp"
#include "pipeline/detail/plan_ribbons.hpp"
#include "pipeline/detail/report_json.hpp"
#include "pipeline/job.hpp"
#include "pipeline/methods/network/network_report.hpp"
#include "pipeline/methods/patterns/pattern_method.hpp"
#include "pipeline/methods/patterns/pattern_report.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/plan_io.hpp"
#include "pipeline/synthesis_job.hpp"
#include "raster/footprint.hpp"
#include "raster/window_index.hpp"
#include "synth/placements_io.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr const char* kPipeline = R"(
version: 1
seed: 11
heightfield: dem.tif
resolution: 10
output: { dir: out, tiles: { size: 24, overlap: 4 } }
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

class PlanFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_dem(dir_ / "dem.tif");  // 64 x 64 cells of 10 m
    std::ostringstream ring;
    ring.precision(10);
    ring << "LINESTRING (";
    for (int i = 0; i <= 48; ++i) {
      const double a = 2.0 * M_PI * (i % 48) / 48.0;
      ring << (i ? ", " : "") << 500320 + 150 * std::cos(a) << ' ' << 5000320 + 150 * std::sin(a);
    }
    ring << ")";
    test::write_layer(dir_ / "map.gpkg", "roads",
                      {{"LINESTRING (500050 5000300, 500590 5000330)", 6.0},
                       {"LINESTRING (500310 5000050, 500330 5000590)", 6.0},
                       {ring.str(), 6.0}});
    const fs::path exemplars = test::source_dir() / "samples/exemplars";
    test::crop_raster(exemplars / "cobble_edging_200x56.png", dir_ / "cobble.png", "PNG", 60, 56);
    test::crop_raster(exemplars / "cobble_edging_200x56_height.tif", dir_ / "cobble_height.tif",
                      "GTiff", 60, 56);
    fs::path file = dir_ / "small.yaml";
    write_file_atomic(file, kPipeline);
    config_ = load_pipeline(file, {{"output.dir", (dir_ / "out").string()}});
  }

  WorldPlan plan() const {
    Warnings warnings;
    return plan_world(config_, {}, warnings);
  }

  static void expect_same_bits(const LayerSet& a, const LayerSet& b, int tile) {
    EXPECT_EQ(a.grid, b.grid) << "tile " << tile;
    ASSERT_EQ(a.layers.size(), b.layers.size()) << "tile " << tile;
    for (std::size_t l = 0; l < a.layers.size(); ++l) {
      EXPECT_EQ(a.layers[l].channels, b.layers[l].channels);
      ASSERT_EQ(a.layers[l].bands.size(), b.layers[l].bands.size());
      for (std::size_t c = 0; c < a.layers[l].bands.size(); ++c) {
        const auto& pa = a.layers[l].bands[c].pixels;
        const auto& pb = b.layers[l].bands[c].pixels;
        ASSERT_EQ(pa.size(), pb.size());
        EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(float)), 0)
            << "tile " << tile << " " << a.layers[l].name << "." << a.layers[l].channels[c];
      }
    }
  }

  test::TempDir dir_;
  PipelineConfig config_;
};

TEST_F(PlanFolder, ALoadedPlanRendersEveryTileBitForBit) {
  const WorldPlan original = plan();
  ASSERT_EQ(original.tiles.size(), 9u);
  ASSERT_EQ(detail::patterns_plan(original)->patterns.size(),
            3u);  // what the round trip must carry
  ASSERT_TRUE(original.heights.heights || original.heights.reader);
  const std::string hash = save_plan(original, dir_ / "plan");
  EXPECT_EQ(plan_hash(dir_ / "plan"), hash);
  const WorldPlan loaded = load_plan(dir_ / "plan");
  ASSERT_EQ(detail::patterns_plan(loaded)->patterns.size(), 3u);
  EXPECT_EQ(detail::patterns_plan(loaded)->patterns[1].synthesis.total_cost,
            detail::patterns_plan(original)->patterns[1].synthesis.total_cost);
  EXPECT_EQ(detail::patterns_plan(loaded)->exemplars.at(0).channel_names,
            detail::patterns_plan(original)->exemplars.at(0).channel_names);
  double pattern_pixels = 0.0;
  for (const TileSpec& tile : original.tiles) {
    const LayerSet a = render_tile(original, tile);
    const LayerSet b = render_tile(loaded, tile);
    expect_same_bits(a, b, tile.index);
    for (const Layer& layer : a.layers)
      for (std::size_t c = 0; c < layer.channels.size(); ++c)
        if (layer.channels[c] == "splat.cobble")
          for (float v : layer.bands[c].pixels) pattern_pixels += v;
  }
  EXPECT_GT(pattern_pixels, 50.0);  // the patterns are there, not only equal
}

TEST_F(PlanFolder, SavingALoadedPlanWritesTheSameFiles) {
  const std::string first = save_plan(plan(), dir_ / "a");
  const std::string second = save_plan(load_plan(dir_ / "a"), dir_ / "b");
  EXPECT_EQ(first, second);
  // The same inputs planned again: the same plan (timings are kept outside its hash).
  EXPECT_EQ(save_plan(plan(), dir_ / "c"), first);
  // A new plan into the same folder keeps unchanged objects and deletes the others.
  WorldPlan other = plan();
  other.render.avoidance_max_distance = 123.0;
  EXPECT_NE(save_plan(other, dir_ / "a"), first);
  std::size_t objects = 0, kept = 0;
  for (const auto& entry : fs::directory_iterator(dir_ / "a/objects")) {
    ++objects;
    kept += fs::exists(dir_ / "b/objects" / entry.path().filename());
  }
  EXPECT_EQ(kept + 1, objects);  // only the settings object changed
}

// The methods' parts of the report (RunReport::method_parts) travel in the plan folder through
// their methods: the same report.json from a loaded plan, timings included, and the patterns'
// per-feature seconds outside the plan's hash.
TEST_F(PlanFolder, TheMethodsReportPartsComeBackWithTheirTimingsOutsideTheHash) {
  WorldPlan original = plan();
  const detail::PatternsReport* patterns = method_report<detail::PatternsReport>(original.report);
  ASSERT_TRUE(patterns);
  ASSERT_TRUE(detail::synthesis_report(original.report, 0, 0));
  const std::string hash = save_plan(original, dir_ / "a");
  const WorldPlan loaded = load_plan(dir_ / "a");
  ASSERT_EQ(loaded.report.method_parts.size(), original.report.method_parts.size());
  EXPECT_EQ(detail::report_to_json(loaded.report, config_, methods_in(loaded)).dump(),
            detail::report_to_json(original.report, config_, methods_in(original)).dump());
  const FeatureSynthesisReport& before = *detail::synthesis_report(original.report, 0, 0);
  const FeatureSynthesisReport& after = *detail::synthesis_report(loaded.report, 0, 0);
  EXPECT_GT(before.avoidance_seconds + before.synthesis_seconds + before.render_seconds, 0.0);
  EXPECT_EQ(after.synthesis_seconds, before.synthesis_seconds);
  EXPECT_EQ(after.exemplar, before.exemplar);
  // Other seconds: the same plan.
  method_report<detail::PatternsReport>(original.report)
      ->features[0][0]
      ->synthesis.synthesis_seconds += 1.0;
  EXPECT_EQ(save_plan(original, dir_ / "b"), hash);
  // Another count: another plan.
  ++method_report<detail::PatternsReport>(original.report)->features[0][0]->synthesis.empty_pieces;
  EXPECT_NE(save_plan(original, dir_ / "c"), hash);
}

TEST_F(PlanFolder, AnObjectThatDoesNotMatchItsHashIsRefusedByName) {
  save_plan(plan(), dir_ / "plan");
  const nlohmann::json doc = nlohmann::json::parse(read_file_bytes(dir_ / "plan/plan.json"));
  const fs::path object = dir_ / "plan" / doc["files"]["ribbons"]["file"].get<std::string>();
  std::string bytes = read_file_bytes(object);
  bytes[bytes.size() / 2] ^= 1;
  write_file_atomic(object, bytes);
  try {
    load_plan(dir_ / "plan");
    FAIL() << "a corrupt object was read";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("files.ribbons"));
    EXPECT_THAT(e.what(), HasSubstr(object.filename().string()));
    EXPECT_THAT(e.what(), HasSubstr("does not match its content hash"));
  }
}

// Every method stores its report part the same way (detail/plan_report_parts.hpp): a network
// class's counts come back as they went, and bytes that are not a part (an intact object, so
// past the hash check) are refused naming plan.json and the method's own key.
TEST_F(PlanFolder, EachMethodsReportPartRoundTripsAndBadBytesNameItsKey) {
  const fs::path dir = dir_ / "parts";
  fs::create_directories(dir / "objects");
  detail::PlanObjects objects(dir);
  for (const SynthesisMethod* method : builtin_synthesis_methods()) {
    const nlohmann::json bad = objects.put_binary("not a report part");
    try {
      method->decode_report(bad, objects);
      FAIL() << method->name() << ": bad bytes were read";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr((dir / "plan.json").string() + ": methods." + method->name() +
                                      ".report"));
    }
  }
  detail::NetworkReport part;
  part.classes.resize(2);
  part.classes[1] = detail::NetworkClassReport{.exemplar = "hedges.gpkg:lines",
                                               .method = "automatic",
                                               .chosen = "quilt",
                                               .lead = "contours",
                                               .lead_bearing_deg = 12.5,
                                               .lines = 17,
                                               .rejected_region = 3};
  const SynthesisMethod& network =
      **std::find_if(builtin_synthesis_methods().begin(), builtin_synthesis_methods().end(),
                     [](const SynthesisMethod* m) { return m->name() == "network"; });
  const std::unique_ptr<MethodPayload> back =
      network.decode_report(network.encode_report(part, objects), objects);
  const auto& decoded = dynamic_cast<const detail::NetworkReport&>(*back);
  ASSERT_EQ(decoded.classes.size(), 2u);
  EXPECT_FALSE(decoded.classes[0]);
  ASSERT_TRUE(decoded.classes[1]);
  EXPECT_EQ(decoded.classes[1]->exemplar, "hedges.gpkg:lines");
  EXPECT_EQ(decoded.classes[1]->chosen, "quilt");
  EXPECT_EQ(decoded.classes[1]->lead, "contours");
  EXPECT_EQ(decoded.classes[1]->lead_bearing_deg, 12.5);
  EXPECT_EQ(decoded.classes[1]->lines, 17);
  EXPECT_EQ(decoded.classes[1]->rejected_region, 3);
}

// A render-tile decodes the ribbons that can reach its tile, not the world's (issue #23 item 4):
// the others are empty in its plan, and every tile renders the bits of the whole plan.
TEST_F(PlanFolder, ATileDecodesOnlyTheRibbonsThatReachItAndRendersTheSameBits) {
  WorldPlan original = plan();
  original.render.avoidance_max_distance = 20.0;  // a reach of 3 pixels: not the whole world
  save_plan(original, dir_ / "plan");
  std::vector<const Ribbon*> all;
  for (const auto& class_ribbons : original.ribbons)
    for (const Ribbon& r : class_ribbons) all.push_back(&r);
  ASSERT_EQ(all.size(), 3u);
  ASSERT_FALSE(original.synthesis_junction_discs.empty());
  ASSERT_FALSE(original.report.classes.empty());
  std::size_t skipped = 0, decoded = 0;
  for (const TileSpec& tile : original.tiles) {
    const WorldPlan part = load_plan_for_tile(dir_ / "plan", tile.index);
    const std::vector<std::size_t> reach = items_meeting(
        original.ribbon_index,
        grow_window(tile.halo_window, avoidance_halo_pixels(original), original.grid));
    std::size_t flat = 0;
    for (std::size_t c = 0; c < part.ribbons.size(); ++c)
      for (const Ribbon& r : part.ribbons[c]) {
        const Ribbon& whole = *all.at(flat);
        if (std::binary_search(reach.begin(), reach.end(), flat++)) {
          ++decoded;
          ASSERT_EQ(r.pieces.size(), whole.pieces.size());
          ASSERT_FALSE(r.pieces.empty());
          EXPECT_EQ(
              std::memcmp(r.pieces.data(), whole.pieces.data(), r.pieces.size() * sizeof(Piece)),
              0);
          EXPECT_EQ(r.centerline.points.size(), whole.centerline.points.size());
          EXPECT_EQ(r.closed, whole.closed);
        } else {
          ++skipped;
          EXPECT_TRUE(r.pieces.empty() && r.centerline.points.empty());
        }
      }
    EXPECT_EQ(flat, all.size());
    // Neither the syntheses' inputs nor the report: a tile's render reads neither.
    EXPECT_TRUE(part.synthesis_junction_discs.empty() && part.synthesis_junctions.empty());
    EXPECT_TRUE(part.report.classes.empty());
    expect_same_bits(render_tile(original, tile), render_tile(part, tile), tile.index);
  }
  EXPECT_GT(skipped, 0u);  // some tile left a ribbon out
  EXPECT_GT(decoded, 0u);
  try {
    load_plan_for_tile(dir_ / "plan", 9);
    FAIL() << "a tile the plan does not have was loaded";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("--tile 9: the plan has 9 tiles (0 to 8)"));
  }
}

// The plan names the DEM (path, options, hash of its bytes) instead of holding its heights: a
// loaded plan reads each tile's window from the file, and refuses a file changed since.
TEST_F(PlanFolder, ThePlanNamesTheDemAndATileReadsOnlyItsWindow) {
  const WorldPlan original = plan();
  ASSERT_TRUE(original.heights.file);
  save_plan(original, dir_ / "plan");
  const nlohmann::json doc = nlohmann::json::parse(read_file_bytes(dir_ / "plan/plan.json"));
  const nlohmann::json& heights = doc["heights"];
  EXPECT_TRUE(heights["raster"].is_null());
  EXPECT_EQ(heights["file"]["path"], fs::absolute(dir_ / "dem.tif").lexically_normal().string());
  EXPECT_EQ(heights["file"]["xxh3_128"], content_hash(read_file_bytes(dir_ / "dem.tif")));
  EXPECT_EQ(heights["file"]["options"]["resolution"], 10.0);

  const WorldPlan loaded = load_plan(dir_ / "plan");
  ASSERT_TRUE(loaded.heights.reader);
  const TileSpec& tile = loaded.tiles.at(4);
  const LayerSet a = render_tile(original, tile);
  const LayerSet b = render_tile(loaded, tile);
  expect_same_bits(a, b, tile.index);
  EXPECT_GT(loaded.heights.reader->cells_read(), 0);
  EXPECT_LE(loaded.heights.reader->cells_read(),
            std::int64_t(tile.halo_window.width) * tile.halo_window.height);

  test::DemSpec changed;
  changed.nodata = -9999.0;  // other bytes at the same path
  test::write_dem(dir_ / "dem.tif", changed);
  try {
    load_plan(dir_ / "plan");
    FAIL() << "a changed DEM was read";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("heights.file"));
    EXPECT_THAT(e.what(), HasSubstr("dem.tif changed after planning"));
  }
}

// With a cache, a tile's result takes its files' digests from the tile cache (hashed as it
// kept them, or checked as it reused them) instead of reading the files again: they must be the
// digests of the files on disk, rendered and reused alike.
TEST_F(PlanFolder, WithACacheATilesResultHoldsTheDigestsOfItsFilesOnDisk) {
  PlanJobOptions options;
  options.output_dir = dir_ / "out";
  options.cache_dir = dir_ / "cache";
  const PlannedJob job = plan_job(config_, options);
  for (const bool reused : {false, true}) {
    render_job_tile(job.plan_dir, 4);
    const nlohmann::json result = nlohmann::json::parse(
        read_file_bytes(job.plan_dir / ("results-" + job.plan) / "tile-4.json"));
    EXPECT_EQ(result["cache"]["reused"], reused);
    ASSERT_FALSE(result["files"].empty());
    for (const nlohmann::json& file : result["files"]) {
      const std::string bytes =
          read_file_bytes(job.plan_dir / ("tiles-" + job.plan) / file["file"].get<std::string>());
      EXPECT_EQ(file["bytes"], bytes.size()) << file["file"];
      EXPECT_EQ(file["xxh3_128"], content_hash(bytes)) << file["file"];
    }
  }
}

TEST_F(PlanFolder, ThreeStepsEqualTheTilesAndRefuseMissingOrChangedTiles) {
  PlanJobOptions options;
  options.output_dir = dir_ / "out";
  const PlannedJob job = plan_job(config_, options);
  ASSERT_EQ(job.tiles, 9u);
  EXPECT_EQ(find_plan_dir(dir_ / "out"), job.plan_dir);
  const WorldPlan loaded = load_plan(job.plan_dir);
  for (int i = 0; i < 9; ++i) {
    if (i != 4) {
      EXPECT_EQ(render_job_tile(job.plan_dir, i).tile, i);
    }
  }
  try {
    finish_job(job.plan_dir);
    FAIL() << "finished without tile 4";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("tile 4 (x1 y1) was not rendered"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "out/report.json"));  // nothing committed
  const TileJobResult four = render_job_tile(job.plan_dir, 4);
  const fs::path tiles = job.plan_dir / ("tiles-" + job.plan) / "tiles";
  const std::string exr = read_file_bytes(tiles / "height_x1_y1.exr");
  // The result's hashes (streamed, in 1 MiB chunks) are those of the files' bytes read whole.
  const nlohmann::json result = nlohmann::json::parse(
      read_file_bytes(job.plan_dir / ("results-" + job.plan) / "tile-4.json"));
  ASSERT_EQ(result["files"].size(), four.files.size());
  ASSERT_FALSE(four.files.empty());
  for (const nlohmann::json& file : result["files"]) {
    const std::string bytes =
        read_file_bytes(job.plan_dir / ("tiles-" + job.plan) / file["file"].get<std::string>());
    EXPECT_EQ(file["bytes"], bytes.size()) << file["file"];
    EXPECT_EQ(file["xxh3_128"], content_hash(bytes)) << file["file"];
  }
  EXPECT_EQ(render_job_tile(job.plan_dir, 4).files, four.files);  // a rerun: the same bytes
  EXPECT_EQ(read_file_bytes(tiles / "height_x1_y1.exr"), exr);
  write_file_atomic(tiles / "splat_x2_y0.tif", "changed");
  try {
    finish_job(job.plan_dir);
    FAIL() << "finished with a changed tile file";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("tile 2: "));
    EXPECT_THAT(e.what(), HasSubstr("splat_x2_y0.tif does not match its recorded hash"));
  }
  render_job_tile(job.plan_dir, 2);
  const RunReport report = finish_job(job.plan_dir);
  EXPECT_EQ(read_file_bytes(dir_ / "out/tiles/height_x1_y1.exr"), exr);
  for (const char* name :
       {"height.vrt", "splat.vrt", "avoidance.vrt", "report.json", "placements/roads_2.json"})
    EXPECT_TRUE(fs::exists(dir_ / "out" / name)) << name;
  const nlohmann::json manifest = nlohmann::json::parse(read_file_bytes(dir_ / "out/report.json"));
  ASSERT_EQ(manifest["tiles"]["tiles"].size(), 9u);
  EXPECT_EQ(manifest["tiles"]["tiles"][4]["index"], 4);
  EXPECT_EQ(detail::pattern_violations(report), 0);
  EXPECT_FALSE(fs::exists(tiles));  // the tiles are the output folder's now
}

TEST_F(PlanFolder, SynthesesAsTasksInTheirDependencyOrderGiveTheSamePlan) {
  PlanJobOptions options;
  options.output_dir = dir_ / "inline";
  const std::string inline_plan = plan_job(config_, options).plan;
  options.output_dir = dir_ / "out";
  options.synthesis_tasks = true;
  const PlannedJob job = plan_job(config_, options);
  ASSERT_EQ(job.syntheses, 3u);
  const auto syntheses = nlohmann::json::parse(read_file_bytes(job.plan_dir / "syntheses.json"));
  const auto& features = syntheses["features"];
  ASSERT_EQ(features.size(), 3u);
  // The two lines cross, the ring crosses both: each waits for every feature before it.
  EXPECT_EQ(features[0]["after"], nlohmann::json::array());
  EXPECT_EQ(features[1]["after"], nlohmann::json({0}));
  EXPECT_EQ(features[2]["after"], nlohmann::json({0, 1}));
  EXPECT_EQ(features[2]["wave"], 2);
  EXPECT_EQ(features[2]["cache"]["why"], "no cache");
  const auto expect_error = [](const auto& step, const std::string& message) {
    try {
      step();
      ADD_FAILURE() << "no error; expected: " << message;
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(message));
    }
  };
  expect_error([&] { render_job_tile(job.plan_dir, 0); }, "syntheses are not in the plan yet");
  expect_error([&] { synthesize_job_feature(job.plan_dir, 2); }, "FID 1: its synthesis");
  expect_error([&] { complete_job_plan(job.plan_dir); }, "not done yet");
  expect_error([&] { synthesize_job_feature(job.plan_dir, 3); }, "the plan has 3 syntheses");
  EXPECT_TRUE(synthesize_job_feature(job.plan_dir, 0).synthesized);
  EXPECT_EQ(synthesize_job_feature(job.plan_dir, 1).name, "roads_2");
  const fs::path entry = fs::path(syntheses["store"].get<std::string>()) / "synthesis" /
                         (features[1]["key"].get<std::string>() + ".twc");
  const std::string first = read_file_bytes(entry);
  synthesize_job_feature(job.plan_dir, 1);  // a rerun (a lost worker): the same bytes
  EXPECT_EQ(read_file_bytes(entry), first);
  synthesize_job_feature(job.plan_dir, 2);
  // The plan the tasks complete is the plan made in one process: the same hash, so the same
  // tiles (every tile of it is tested bit for bit above).
  const PlannedJob complete = complete_job_plan(job.plan_dir);
  EXPECT_EQ(complete.plan, inline_plan);
  EXPECT_EQ(plan_hash(job.plan_dir), inline_plan);
  EXPECT_EQ(complete_job_plan(job.plan_dir).plan, inline_plan);  // complete already: no change
  expect_error([&] { synthesize_job_feature(job.plan_dir, 0); }, "complete already");
  EXPECT_EQ(detail::patterns_plan(load_plan(job.plan_dir))->patterns.size(), 3u);
  EXPECT_EQ(render_job_tile(job.plan_dir, 4).tile, 4);
}

// Issue #24 item 10: a synthesis task whose exemplar was replaced after planning names the
// exemplar file and says to plan again; a truncated store entry of a feature it depends on is
// named as corrupt, with its path and the task that makes it again (never "not done yet").
TEST_F(PlanFolder, SynthesisTasksNameAChangedExemplarAndACorruptStoreEntry) {
  PlanJobOptions options;
  options.output_dir = dir_ / "out";
  options.synthesis_tasks = true;
  const PlannedJob job = plan_job(config_, options);
  ASSERT_EQ(job.syntheses, 3u);
  const auto syntheses = nlohmann::json::parse(read_file_bytes(job.plan_dir / "syntheses.json"));
  ASSERT_TRUE(synthesize_job_feature(job.plan_dir, 0).synthesized);
  const fs::path entry = fs::path(syntheses["store"].get<std::string>()) / "synthesis" /
                         (syntheses["features"][0]["key"].get<std::string>() + ".twc");
  ASSERT_TRUE(fs::is_regular_file(entry));
  fs::resize_file(entry, fs::file_size(entry) / 2);
  try {
    synthesize_job_feature(job.plan_dir, 1);
    ADD_FAILURE() << "a truncated entry of feature 0 was not reported";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(),
                HasSubstr("features.roads: FID " + syntheses["features"][0]["fid"].dump() +
                          ": synthesis store cache entry " + entry.string() + " is corrupt ("));
    EXPECT_THAT(e.what(), HasSubstr("delete that file and synthesize the feature again "
                                    "(terraweave synth-feature " +
                                    job.plan_dir.string() + " --feature 0)"));
    EXPECT_THAT(e.what(), Not(HasSubstr("not done yet")));
  }
  // The exemplar replaced by another image: feature 0's task names it.
  test::crop_raster(test::source_dir() / "samples/exemplars/cobble_bed_260x80.png",
                    dir_ / "cobble.png", "PNG", 60, 56);
  try {
    synthesize_job_feature(job.plan_dir, 0);
    ADD_FAILURE() << "a changed exemplar was not reported";
  } catch (const Error& e) {
    EXPECT_THAT(
        e.what(),
        HasSubstr("feature 0 (" + syntheses["features"][0]["name"].get<std::string>() +
                  "): features.roads.synthesis.exemplars " + (dir_ / "cobble.png").string() +
                  " changed after planning; plan again (terraweave plan"));
    EXPECT_THAT(e.what(), Not(HasSubstr("program version")));
  }
}

// Issue #24: a deleted syntheses.json is an error naming it, never "no syntheses" (which
// committed a world without its patterns); once the plan is complete it is not needed.
TEST_F(PlanFolder, AMissingSynthesesFileIsAnErrorUntilThePlanIsComplete) {
  PlanJobOptions options;
  options.output_dir = dir_ / "out";
  options.synthesis_tasks = true;
  const PlannedJob job = plan_job(config_, options);
  ASSERT_EQ(job.syntheses, 3u);
  const fs::path list = job.plan_dir / "syntheses.json";
  const std::string kept = read_file_bytes(list);
  fs::remove(list);
  for (const auto& step : std::vector<std::function<void()>>{
           [&] { complete_job_plan(job.plan_dir); }, [&] { render_job_tile(job.plan_dir, 0); },
           [&] { finish_job(job.plan_dir); }}) {
    try {
      step();
      ADD_FAILURE() << "a missing syntheses.json was read as no syntheses";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("syntheses.json: missing, but plan"));
      EXPECT_THAT(e.what(), HasSubstr("has 3 syntheses to run and complete"));
    }
  }
  EXPECT_FALSE(fs::exists(dir_ / "out/report.json"));  // nothing committed
  // Put back, the tasks run and the plan completes; then the file is no longer needed.
  std::ofstream(list, std::ios::binary) << kept;
  for (int f = 0; f < 3; ++f) synthesize_job_feature(job.plan_dir, f);
  const PlannedJob complete = complete_job_plan(job.plan_dir);
  fs::remove(list);
  EXPECT_EQ(complete_job_plan(job.plan_dir).plan, complete.plan);
  EXPECT_EQ(render_job_tile(job.plan_dir, 4).tile, 4);
  EXPECT_EQ(detail::patterns_plan(load_plan(job.plan_dir))->patterns.size(), 3u);
}

// Issue #24 item 3: the plan folder's own files are checked like its objects. An edited tile
// window (tasks.json), an edited field of plan.json, an edited syntheses.json are errors naming
// the file and the command that plans again; nothing is rendered from them.
TEST_F(PlanFolder, EditedPlanFilesAreRefusedByName) {
  PlanJobOptions options;
  options.output_dir = dir_ / "out";
  options.synthesis_tasks = true;
  const PlannedJob job = plan_job(config_, options);
  ASSERT_EQ(job.syntheses, 3u);
  const auto edited = [&](const std::string& file, const std::function<void(nlohmann::json&)>& edit,
                          const std::function<void()>& step, const std::string& message) {
    const fs::path path = job.plan_dir / file;
    const std::string kept = read_file_bytes(path);
    nlohmann::json j = nlohmann::json::parse(kept);
    edit(j);
    write_file_atomic(path, j.dump(1) + "\n");
    try {
      step();
      ADD_FAILURE() << "an edited " << file << " was used";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(path.string() + ": " + message)) << file;
      EXPECT_THAT(e.what(), HasSubstr("terraweave plan " + (dir_ / "small.yaml").string() +
                                      " --out " + (dir_ / "out").string()))
          << file;  // what to do
      EXPECT_THAT(e.what(), HasSubstr("--synthesis tasks")) << file;
    }
    write_file_atomic(path, kept);
  };
  const auto load = [&] { load_plan(job.plan_dir); };
  const auto synthesize = [&] { synthesize_job_feature(job.plan_dir, 0); };
  edited(
      "tasks.json", [](auto& j) { j["tiles"][4]["window"]["col0"] = 9; }, load,
      "does not match its hash in plan.json");
  edited(
      "plan.json", [](auto& j) { j["tiles"]["overlap"] = 3; }, load,
      "its fields do not match the plan's hash");
  edited(
      "plan.json", [](auto& j) { j["output_window"]["width"] = 10; }, synthesize,
      "its fields do not match the plan's hash");
  edited(
      "syntheses.json", [](auto& j) { j["features"][1]["key"] = std::string(32, '0'); }, synthesize,
      "does not match its hash in job.json");
  edited(
      "syntheses.json", [](auto& j) { j["features"][0]["task"] = false; },
      [&] { complete_job_plan(job.plan_dir); }, "does not match its hash in job.json");
  // A dependency graph that cannot be: named before the hash is compared.
  edited(
      "syntheses.json",
      [](auto& j) {
        j["features"][2]["after"] = {0, 999};
      },
      synthesize, "feature 2 (roads_3) depends on 999, which is not in the list (features 0 to 2)");
  edited(
      "syntheses.json", [](auto& j) { j["features"][1]["after"] = {1}; }, synthesize,
      "feature 1 (roads_2) depends on itself");
  edited(
      "syntheses.json", [](auto& j) { j["features"][0]["after"] = {2}; }, synthesize,
      "a dependency cycle: feature 0 -> 2 -> 0");
  {  // a missing tasks.json is named too
    const std::string kept = read_file_bytes(job.plan_dir / "tasks.json");
    fs::remove(job.plan_dir / "tasks.json");
    try {
      load_plan(job.plan_dir);
      ADD_FAILURE() << "a plan without tasks.json loaded";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("tasks.json: missing; plan again (terraweave plan "));
    }
    write_file_atomic(job.plan_dir / "tasks.json", kept);
  }
  // Put back, every file is whole again: the plan loads and the tasks run.
  EXPECT_EQ(load_plan(job.plan_dir).tiles.size(), 9u);
  EXPECT_TRUE(synthesize_job_feature(job.plan_dir, 0).synthesized);
}

TEST(SynthesisGraph, UnknownSelfCyclesAndLaterDependenciesAreNamed) {
  const auto graph = [](std::vector<std::vector<int>> after) {
    nlohmann::json features = nlohmann::json::array();
    for (std::size_t i = 0; i < after.size(); ++i)
      features.push_back({{"index", i}, {"name", "r" + std::to_string(i)}, {"after", after[i]}});
    return features;
  };
  const auto error = [](const nlohmann::json& features) -> std::string {
    try {
      detail::check_synthesis_graph(features, "s.json", "plan again");
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error(graph({{}, {0}, {0, 1}})), "");
  EXPECT_THAT(error(graph({{}, {-1}})), HasSubstr("feature 1 (r1) depends on -1, which is not"));
  EXPECT_THAT(error(graph({{}, {5}})), HasSubstr("depends on 5, which is not in the list"));
  EXPECT_THAT(error(graph({{0}})), HasSubstr("feature 0 (r0) depends on itself; plan again"));
  EXPECT_THAT(error(graph({{}, {2}, {3}, {1}})),
              HasSubstr("a dependency cycle: feature 1 -> 2 -> 3 -> 1"));
  EXPECT_THAT(error(graph({{1}, {}})),
              HasSubstr("feature 0 (r0) depends on 1, which is synthesized after it"));
  nlohmann::json wrong_index = graph({{}, {0}});
  wrong_index[1]["index"] = 7;
  EXPECT_THAT(error(wrong_index), HasSubstr("features[1]: `index` is not 1"));
}

// The plan's binary objects (detail/plan_binary.hpp): exact values (NaN, -0, optional, nested
// vectors) back, and bytes that are short or too long are one error naming the object.
TEST(PlanBinary, ValuesComeBackExactlyAndBadBytesAreOneClearError) {
  std::vector<std::vector<Ribbon>> ribbons(2);
  Curve line{{{0.0, 0.0}, {10.0, 0.5}, {20.0, -0.0}, {31.0, 2.0}}, false};
  ribbons[1].push_back(make_ribbon(line, {4.0, 5.0, 0.0}));
  ribbons[1].push_back(Ribbon{});  // a feature too short for a ribbon
  ribbons[1].push_back(make_ribbon(line, {2.0, 3.0, 0.0}));
  const std::optional<double> nodata = std::nan("");
  const std::string bytes = detail::ribbons_to_bytes(ribbons);
  std::vector<std::vector<Ribbon>> back;
  detail::ribbons_from_bytes(bytes, back, nullptr, "test: ribbons");
  ASSERT_EQ(back.size(), 2u);
  ASSERT_EQ(back[1].size(), 3u);
  EXPECT_TRUE(back[0].empty());
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(detail::to_bytes(back[1][i]), detail::to_bytes(ribbons[1][i])) << i;
    EXPECT_EQ(back[1][i].pieces.size(), ribbons[1][i].pieces.size());
  }
  EXPECT_GT(back[1][2].pieces.size(), 5u);
  const std::vector<std::size_t> only = {2};  // flat index: class 1, ribbon 1
  detail::ribbons_from_bytes(bytes, back, &only, "test: ribbons");
  EXPECT_TRUE(back[1][0].pieces.empty());
  EXPECT_EQ(back[1][1].pieces.size(), 0u);
  EXPECT_EQ(back[1][2].pieces.size(), ribbons[1][2].pieces.size());

  std::optional<double> nodata_back;
  detail::from_bytes(detail::to_bytes(nodata), nodata_back, "test: nodata");
  ASSERT_TRUE(nodata_back.has_value());
  EXPECT_TRUE(std::isnan(*nodata_back));

  const std::string whole = detail::to_bytes(ribbons);
  for (const std::string& bad : {whole.substr(0, whole.size() - 3), whole + "x"}) {
    try {
      detail::from_bytes(bad, back, "plan P: ribbons");
      FAIL() << "bad bytes were read";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("plan P: ribbons: "));
    }
  }
  try {  // a count larger than the bytes left never allocates
    std::string huge = whole;
    const std::uint64_t count = std::uint64_t(1) << 60;
    std::memcpy(huge.data(), &count, sizeof count);
    detail::from_bytes(huge, back, "plan P: ribbons");
    FAIL() << "a corrupt count was read";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("more than the object holds"));
  }
  try {
    detail::ribbons_from_bytes(bytes.substr(0, bytes.size() - 1), back, nullptr, "plan P: ribbons");
    FAIL() << "short ribbons were read";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("plan P: ribbons: "));
  }
}

// The patterns method's objects (plan version 10): a pattern comes back with its synthesis as
// its placements file holds it (a mix's atlas columns and exemplars included), the values the
// file does not hold are not kept, and a placement outside the mix is refused by name.
TEST(PlanBinary, APatternComesBackAsItsPlacementsFileHoldsIt) {
  detail::PlannedPattern pattern;
  pattern.class_index = 2;
  pattern.exemplar_index = 1;
  pattern.window = {3, 4, 50, 60};
  pattern.feather = 0.25;
  pattern.targets.push_back({3, true, 0, false});
  Synthesis& s = pattern.synthesis;
  s.column = 7;
  s.total_cost = 123;
  s.objective_cost = 456;  // not in a placements file
  s.mean_seam_cost = 0.1;
  s.valid_counts = {4, 5};
  s.mix = MixLayout{{0, 70}, {60, 40}, {56, 50}, 10};
  s.pieces_per_exemplar = {1, 1};
  s.exemplar_switches = 1;
  for (int i = 0; i < 2; ++i) {
    Placement& p = s.placements.emplace_back();
    p.ux = 70 * i + 3;
    p.uy = -2;
    p.exemplar = i;
    p.origin = {500000.125 + i, 5000000.3};
    p.along = {std::sqrt(0.5), std::sqrt(0.5)};
    p.across = {-std::sqrt(0.5), std::sqrt(0.5)};
    p.scale = 1.0 / 3.0;
    p.stitch = {0.5f, 1.75f};
  }
  const std::string bytes = detail::pattern_to_bytes(pattern);
  detail::PlannedPattern back;
  detail::pattern_from_bytes(bytes, back, "plan P: pattern");
  EXPECT_EQ(back.class_index, 2u);
  EXPECT_EQ(back.window, pattern.window);
  EXPECT_EQ(back.feather, 0.25);
  ASSERT_EQ(back.targets.size(), 1u);
  EXPECT_TRUE(back.targets[0].to_height);
  EXPECT_EQ(back.synthesis.objective_cost, 0);
  Synthesis expected = s;
  expected.objective_cost = 0;
  EXPECT_EQ(placements_to_json(back.synthesis, ""), placements_to_json(expected, ""));
  ASSERT_EQ(back.synthesis.placements.size(), 2u);
  EXPECT_EQ(back.synthesis.placements[1].ux, 73);
  EXPECT_EQ(back.synthesis.placements[1].exemplar, 1);
  EXPECT_EQ(back.synthesis.placements[0].scale, 1.0 / 3.0);
  EXPECT_EQ(detail::pattern_to_bytes(back), bytes);

  // The last placement's exemplar, 77 bytes before the end (ux, uy: 8 bytes; then exemplar,
  // empty, three Vec2, scale and the stitch's count and two floats: 85 bytes), made 5.
  std::string outside = bytes;
  const std::int32_t five = 5;
  std::memcpy(outside.data() + outside.size() - 77, &five, sizeof five);
  try {
    detail::pattern_from_bytes(outside, back, "plan P: pattern");
    FAIL() << "a placement outside the mix was read";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("plan P: pattern"));
  }
  try {
    detail::pattern_from_bytes(bytes.substr(0, bytes.size() - 1), back, "plan P: pattern");
    FAIL() << "a short pattern was read";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("plan P: pattern: "));
  }
}

}  // namespace
}  // namespace tw
