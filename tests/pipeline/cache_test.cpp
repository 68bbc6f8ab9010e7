// Incremental rebuilds with --cache (docs/cache.md, issue #10 item 3), feature syntheses: one
// changed road rebuilds exactly the syntheses whose inputs changed (worked out from the geometry
// in cache_world.cpp, independently of the cache), a corrupt entry is detected and rebuilt, and
// every output equals a clean run's, byte for byte.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "cache_world.hpp"
#include "core/error.hpp"
#include "file_edit.hpp"
#include "pipeline/detail/cache_entry.hpp"
#include "pipeline/detail/plan_stage_cache.hpp"
#include "pipeline/job.hpp"
#include "pipeline/run.hpp"
#include "pipeline/synthesis_job.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using namespace tw::test;

// --- Runs ---------------------------------------------------------------------------------------
class CacheRun : public ::testing::Test {
 protected:
  void SetUp() override {
    write_roads(dir_ / "roads.gpkg", roads());
    write_exemplar(dir_.path());
  }

  RunReport run(const std::string& out, bool with_cache = true, const std::string& extra = "",
                std::vector<Override> overrides = {}) {
    overrides.push_back({"output.dir", (dir_ / out).string()});
    const PipelineConfig config =
        parse_pipeline(std::string(kCachePipeline) + extra, "cache.yaml", dir_.path(), overrides);
    RunOptions options;
    if (with_cache) options.cache_dir = dir_ / "cache";
    return run_pipeline(config, options);
  }

  // FID -> cache status of each road, as report.json lists them.
  std::map<std::int64_t, nlohmann::json> statuses(const std::string& out) const {
    std::ifstream in(dir_ / out / "report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    std::map<std::int64_t, nlohmann::json> by_fid;
    for (const auto& f : report["classes"][0]["features"]) by_fid[f["fid"]] = f["cache"];
    return by_fid;
  }

  std::set<int> rebuilt(const std::string& out) const {
    std::set<int> fids;
    for (const auto& [fid, cache] : statuses(out))
      if (cache["status"] == "rebuilt") fids.insert(int(fid));
    return fids;
  }

  void expect_same_outputs(const std::string& a, const std::string& b) const {
    EXPECT_GT(expect_same_output_files(dir_ / a, dir_ / b), 5u);
  }

  test::TempDir dir_;
};

TEST_F(CacheRun, ExpectedRebuildsOfTheTestGeometry) {
  // The change touches R1, its crossing with R2, and brings R1's canvas onto R4's.
  EXPECT_EQ(expected_rebuilds(roads(), roads_with_r1_moved()), (std::set<int>{1, 2, 4}));
}

TEST_F(CacheRun, WithoutCacheEveryFeatureIsRebuiltAndKeyed) {
  run("plain", false);
  for (const auto& [fid, cache] : statuses("plain")) {
    EXPECT_EQ(cache["status"], "rebuilt") << fid;
    EXPECT_EQ(cache["why"], "no cache") << fid;
    EXPECT_EQ(cache["key"].get<std::string>().size(), 32u) << fid;
  }
}

TEST_F(CacheRun, UnchangedRerunReusesEverythingWithTheSameBytes) {
  run("first");
  EXPECT_EQ(rebuilt("first"), (std::set<int>{1, 2, 3, 4, 5}));
  for (const auto& [fid, cache] : statuses("first")) EXPECT_EQ(cache["why"], "new") << fid;
  run("second");
  EXPECT_EQ(rebuilt("second"), std::set<int>{});
  for (const auto& [fid, cache] : statuses("second")) {
    EXPECT_EQ(cache["why"], "unchanged") << fid;
    EXPECT_EQ(cache["key"], statuses("first")[fid]["key"]) << fid;
  }
  expect_same_outputs("first", "second");
}

TEST_F(CacheRun, OneChangedRoadRebuildsExactlyWhatItReaches) {
  run("before");
  write_roads(dir_ / "roads.gpkg", roads_with_r1_moved());
  run("after");
  // The keys that change: R1, R2 and R4 (R1's canvas now overlaps R4's).
  EXPECT_EQ(expected_rebuilds(roads(), roads_with_r1_moved()), (std::set<int>{1, 2, 4}));
  const auto status = statuses("after");
  EXPECT_EQ(status.at(1)["why"], "geometry changed");
  EXPECT_EQ(status.at(2)["why"], "avoidance changed");  // the junction disc moved
  // R1's coverage stays off the pixels R4's DP reads: the finer check reuses it.
  EXPECT_EQ(status.at(4)["status"], "reused");
  EXPECT_EQ(status.at(4)["why"], "earlier feature changed, mask the same");
  EXPECT_EQ(status.at(3)["why"], "unchanged");
  EXPECT_EQ(rebuilt("after"), (std::set<int>{1, 2}));
  run("clean", false);
  expect_same_outputs("after", "clean");
}

// --- The finer check (issue #23 item 2): keyed by what the DP reads -----------------------------
// F1 runs diagonally; F2 lies inside F1's canvas box, 100 m or more from F1's line: their
// canvases overlap, F1's coverage never reaches F2's.
std::vector<Line> diagonal_roads() {
  return {{{50, 50}, {300, 300}}, {{200, 80}, {290, 80}}};
}
// F1's far end moved: its key changes, and so F2's earlier part; F2's DP reads the same.
std::vector<Line> diagonal_far_end_moved() {
  std::vector<Line> lines = diagonal_roads();
  lines[0][1] = {300, 310};
  return lines;
}
// F1's start moved so that it passes 1.5 m west of F2's west end (no crossing): its coverage
// now lies on F2's canvas.
std::vector<Line> diagonal_passing_f2() {
  std::vector<Line> lines = diagonal_roads();
  lines[0][0] = {180, 40};
  return lines;
}

TEST_F(CacheRun, AnEarlierChangeOffTheMaskItReadsReusesTheSynthesis) {
  ASSERT_TRUE(crossings(diagonal_far_end_moved()).empty());
  write_roads(dir_ / "roads.gpkg", diagonal_roads());
  run("before");
  write_roads(dir_ / "roads.gpkg", diagonal_far_end_moved());
  run("after");
  const auto status = statuses("after");
  EXPECT_EQ(status.at(1)["why"], "geometry changed");
  EXPECT_EQ(status.at(2)["status"], "reused");
  EXPECT_EQ(status.at(2)["why"], "earlier feature changed, mask the same");
  EXPECT_NE(status.at(2)["key"], statuses("before").at(2)["key"]);  // the coarse key missed
  EXPECT_EQ(rebuilt("after"), std::set<int>{1});
  run("clean", false);
  expect_same_outputs("after", "clean");  // F2's placements and tiles included
  run("again");                           // kept under its new key: found by that alone
  EXPECT_EQ(statuses("again").at(2)["why"], "unchanged");
  EXPECT_EQ(rebuilt("again"), std::set<int>{});
}

TEST_F(CacheRun, AnEarlierChangeOnTheMaskItReadsResynthesizes) {
  ASSERT_TRUE(crossings(diagonal_passing_f2()).empty());
  write_roads(dir_ / "roads.gpkg", diagonal_roads());
  run("before");
  write_roads(dir_ / "roads.gpkg", diagonal_passing_f2());
  run("after");
  const auto status = statuses("after");
  EXPECT_EQ(status.at(2)["status"], "rebuilt");
  EXPECT_EQ(status.at(2)["why"], "earlier feature changed");
  EXPECT_EQ(rebuilt("after"), (std::set<int>{1, 2}));
  run("clean", false);
  expect_same_outputs("after", "clean");
}

// F1 is an L along the west and north edges: its canvas box holds the whole world, but the DP
// reads only the canvas tiles (256 cells) its pieces meet. F2 and F3 cross in the middle,
// 200 m from F1's line, on a tile F1 does not read: the junction disc's box meets F1's canvas.
std::vector<Line> l_and_a_crossing(double f2_x) {
  return {{{50, 50}, {50, 600}, {600, 600}}, {{f2_x, 180}, {f2_x, 260}}, {{390, 220}, {470, 220}}};
}

TEST_F(CacheRun, AnAvoidanceChangeOffTheTilesItReadsReusesTheSynthesis) {
  write_roads(dir_ / "roads.gpkg", l_and_a_crossing(430));
  run("before");
  write_roads(dir_ / "roads.gpkg", l_and_a_crossing(432));  // the crossing moves 2 m east
  run("after");
  const auto status = statuses("after");
  EXPECT_EQ(status.at(1)["status"], "reused");
  EXPECT_EQ(status.at(1)["why"], "avoidance changed, mask the same");
  EXPECT_EQ(status.at(2)["why"], "geometry changed");
  EXPECT_EQ(status.at(3)["why"], "avoidance changed");  // the disc moved on its own pixels
  EXPECT_EQ(rebuilt("after"), (std::set<int>{2, 3}));
  run("clean", false);
  expect_same_outputs("after", "clean");
}

// The same in a job (docs/distributed.md): the plan finds F1's key missed in its avoidance part
// only, so F1 is a task; the task makes F1's avoidance, finds the stored placements whose DP read
// the same and reuses them (its result says why). The job's report lists a cached run's
// statuses, its outputs are a clean run's bytes.
TEST_F(CacheRun, ASynthesisTaskAppliesTheFinerCheckAsARunDoes) {
  constexpr const char* kTiles = "output: { tiles: { size: 64, overlap: 4 } }\n";
  // A file: job.json names it, and every task reads it again.
  const fs::path file = dir_ / "cache.yaml";
  std::ofstream(file) << kCachePipeline << kTiles;
  const auto config = [&](const std::string& out) {
    return load_pipeline(file, {{"output.dir", (dir_ / out).string()}});
  };
  write_roads(dir_ / "roads.gpkg", l_and_a_crossing(430));
  run("before", true, kTiles);
  fs::copy(dir_ / "cache", dir_ / "run-cache", fs::copy_options::recursive);
  write_roads(dir_ / "roads.gpkg", l_and_a_crossing(432));

  PlanJobOptions options;
  options.output_dir = dir_ / "job";
  options.cache_dir = dir_ / "cache";
  options.synthesis_tasks = true;
  const PlannedJob job = plan_job(config("job"), options);
  const nlohmann::json syntheses =
      nlohmann::json::parse(read_file(job.plan_dir / "syntheses.json"));
  const nlohmann::json& f1 = syntheses["features"][0];
  ASSERT_EQ(f1["fid"], 1);
  EXPECT_EQ(f1["task"], true);  // the coarse key missed
  EXPECT_EQ(f1["cache"]["why"], "avoidance changed");
  EXPECT_EQ(job.syntheses, 3u);
  for (std::size_t i = 0; i < syntheses["features"].size(); ++i) {
    const SynthesisJobResult task = synthesize_job_feature(job.plan_dir, int(i));
    const nlohmann::json& planned = syntheses["features"][i];
    if (i == 0) {  // F1's task reused, and says why (synth-feature prints it)
      EXPECT_FALSE(task.synthesized);
      EXPECT_EQ(task.why, "avoidance changed, mask the same");
    } else if (planned["task"] == true) {
      EXPECT_TRUE(task.synthesized) << planned["name"];
      EXPECT_EQ(task.why, "") << planned["name"];
    } else {  // reused by the plan
      EXPECT_FALSE(task.synthesized) << planned["name"];
      EXPECT_EQ(task.why, planned["cache"]["why"]) << planned["name"];
    }
  }
  const nlohmann::json result = nlohmann::json::from_cbor(
      read_file(job.plan_dir / "synthesis-results" / (f1["key"].get<std::string>() + ".cbor")));
  EXPECT_EQ(result["cache"]["reused"], true);
  EXPECT_EQ(result["cache"]["why"], "avoidance changed, mask the same");
  const PlannedJob complete = complete_job_plan(job.plan_dir);
  for (std::size_t t = 0; t < complete.tiles; ++t) render_job_tile(job.plan_dir, int(t));
  finish_job(job.plan_dir);

  const auto status = statuses("job");
  EXPECT_EQ(status.at(1)["status"], "reused");
  EXPECT_EQ(status.at(1)["why"], "avoidance changed, mask the same");
  EXPECT_EQ(rebuilt("job"), (std::set<int>{2, 3}));
  RunOptions cached;  // a run from the cache as the job found it
  cached.cache_dir = dir_ / "run-cache";
  run_pipeline(config("after"), cached);
  EXPECT_EQ(status, statuses("after"));
  expect_same_outputs("job", "after");
  run_pipeline(config("clean"), {});  // the same file: the tiles name it
  expect_same_outputs("job", "clean");
}

// The index the finer check reads, corrupt, and an entry of an older layout (no input hash)
// reached through it: each a warning, and the synthesis rebuilt.
TEST_F(CacheRun, ACorruptInputIndexOrAnEntryWithoutItsInputHashIsAWarningAndRebuilt) {
  const auto corrupt_warnings = [](const RunReport& report) {
    std::vector<std::string> messages;
    for (const Warning& w : report.warnings)
      if (w.code == "cache_corrupt") messages.push_back(w.message);
    return messages;
  };
  const auto fill_then_move_f1 = [&] {  // F2 would be reused by the finer check
    fs::remove_all(dir_ / "cache");
    write_roads(dir_ / "roads.gpkg", diagonal_roads());
    run("before");
    write_roads(dir_ / "roads.gpkg", diagonal_far_end_moved());
  };
  fill_then_move_f1();
  for (const auto& e : fs::directory_iterator(dir_ / "cache/synthesis/inputs"))
    fs::resize_file(e.path(), fs::file_size(e.path()) - 3);
  const std::vector<std::string> truncated = corrupt_warnings(run("truncated"));
  ASSERT_EQ(truncated.size(), 1u);  // F2's record (F1's geometry changed: not looked up)
  EXPECT_THAT(truncated[0], HasSubstr("synthesis/inputs/"));
  EXPECT_EQ(statuses("truncated").at(2)["why"], "corrupt entry");
  EXPECT_EQ(rebuilt("truncated"), (std::set<int>{1, 2}));

  fill_then_move_f1();
  const fs::path entry =
      dir_ / "cache/synthesis" / (statuses("before").at(2)["key"].get<std::string>() + ".twc");
  detail::CacheRead read = detail::read_cache_entry(entry);
  ASSERT_EQ(read.state, detail::CacheRead::State::ok);
  nlohmann::json meta = nlohmann::json::parse(read.sections.at("meta"));
  ASSERT_TRUE(meta.contains("input"));
  meta.erase("input");  // as format 2 wrote it, with a valid checksum
  read.sections["meta"] = meta.dump();
  detail::write_cache_entry(entry, read.sections);
  const std::vector<std::string> old = corrupt_warnings(run("old"));
  ASSERT_EQ(old.size(), 1u);
  EXPECT_THAT(old[0], HasSubstr(entry.string()));
  EXPECT_EQ(statuses("old").at(2)["why"], "corrupt entry");
  EXPECT_EQ(rebuilt("old"), (std::set<int>{1, 2}));

  run("clean", false);
  expect_same_outputs("truncated", "clean");
  expect_same_outputs("old", "clean");
}

// report.json without what may differ between two runs of the same inputs: timings, cache
// statuses and the output folder's name. Counts the values it keeps.
nlohmann::json without_timings(nlohmann::json j, std::size_t& values) {
  if (j.is_object()) {
    nlohmann::json kept = nlohmann::json::object();
    for (auto& [key, value] : j.items()) {
      if (key.ends_with("seconds") || key == "stages" || key == "started_utc" || key == "cache" ||
          key == "timings" || key == "overrides" || key == "dir")
        continue;
      kept[key] = without_timings(value, values);
    }
    return kept;
  }
  if (j.is_array()) {
    for (auto& item : j) item = without_timings(item, values);
    return j;
  }
  ++values;
  return j;
}

// Issue #24 item 4: a reused synthesis reports what its synthesis reported (coverage, objective,
// parametric seam cost...), not zeros: report.json of a cached rerun is a clean run's.
TEST_F(CacheRun, CachedRerunReportsEveryValueOfACleanRun) {
  run("first");
  run("second");
  ASSERT_EQ(rebuilt("second"), std::set<int>{});
  run("clean", false);
  const auto report = [&](const std::string& out, std::size_t& values) {
    std::ifstream in(dir_ / out / "report.json");
    return without_timings(nlohmann::json::parse(in), values);
  };
  std::size_t values = 0, clean_values = 0;
  const nlohmann::json cached = report("second", values), clean = report("clean", clean_values);
  EXPECT_GT(values, 200u);  // every field of every feature compared
  EXPECT_EQ(values, clean_values);
  for (const auto& f : cached["classes"][0]["features"]) {
    const nlohmann::json& s = f["synthesis"];
    EXPECT_GT(s["coverage_ratio"].get<double>(), 0.0) << f["fid"];
    EXPECT_GT(s["mean_coverage"].get<double>(), 0.0) << f["fid"];
    EXPECT_FALSE(s["objective"].get<std::string>().empty()) << f["fid"];
  }
  EXPECT_EQ(cached.dump(1), clean.dump(1));
}

// Issue #24 item 4: the tile key holds everything that reaches a tile's bytes, the seed (in the
// GeoTIFFs' metadata) included: a seed-9 run from a cache filled at seed 7 writes a clean seed-9
// run's bytes.
TEST_F(CacheRun, TileKeyHoldsTheSeed) {
  const std::string tiled = "output: { tiles: { size: 80, overlap: 2 } }\n";
  run("seed7", true, tiled, {{"seed", "7"}});
  run("seed9", true, tiled, {{"seed", "9"}});
  run("clean9", false, tiled, {{"seed", "9"}});
  expect_same_outputs("seed9", "clean9");
  const std::string tif = test::read_file(dir_ / "seed9/tiles/height_x0_y0.tif");
  EXPECT_NE(tif.find("TERRAWEAVE_SEED\">9<"), std::string::npos);
  EXPECT_EQ(tif.find("TERRAWEAVE_SEED\">7<"), std::string::npos);
}

TEST_F(CacheRun, CorruptEntriesAreDetectedAndRebuilt) {
  run("first");
  const auto keys = statuses("first");
  const auto entry = [&](std::int64_t fid) {
    return dir_ / "cache/synthesis" / (keys.at(fid)["key"].get<std::string>() + ".twc");
  };
  ASSERT_TRUE(fs::exists(entry(3)));
  {  // one byte of R3's entry flipped, in its placements
    std::string bytes = test::read_file(entry(3));
    bytes[bytes.size() / 2] ^= 0x20;
    std::ofstream(entry(3), std::ios::binary | std::ios::trunc) << bytes;
  }
  fs::resize_file(entry(5), fs::file_size(entry(5)) - 7);  // R5's truncated
  const RunReport report = run("second");
  const auto status = statuses("second");
  EXPECT_EQ(status.at(3)["status"], "rebuilt");
  EXPECT_EQ(status.at(3)["why"], "corrupt entry");
  EXPECT_EQ(status.at(5)["why"], "corrupt entry");
  EXPECT_EQ(rebuilt("second"), (std::set<int>{3, 5}));
  int corrupt = 0;
  for (const Warning& w : report.warnings) {
    if (w.code != "cache_corrupt") continue;
    ++corrupt;
    EXPECT_THAT(w.message, HasSubstr(".twc"));
  }
  EXPECT_EQ(corrupt, 2);
  expect_same_outputs("first", "second");
  run("third");  // the rebuilt entries are whole again
  EXPECT_EQ(rebuilt("third"), std::set<int>{});
  expect_same_outputs("first", "third");
}

// Issue #24 item 8: a cache that cannot be written is a warning, and the run goes on without
// it, its outputs those of a run without a cache.
TEST_F(CacheRun, ACacheThatCannotBeCreatedIsAWarningAndTheRunGoesOnWithoutIt) {
  run("plain", false);
  std::ofstream(dir_ / "blocker") << "a file where the cache's parent folder should be\n";
  const PipelineConfig config = parse_pipeline(kCachePipeline, "cache.yaml", dir_.path(),
                                               {{"output.dir", (dir_ / "blocked").string()}});
  RunOptions options;
  options.cache_dir = dir_ / "blocker/cache";
  const RunReport report = run_pipeline(config, options);
  int unwritable = 0;
  for (const Warning& w : report.warnings) {
    if (w.code != "cache_unwritable") continue;
    ++unwritable;
    EXPECT_EQ(w.subject, "cache");
    EXPECT_THAT(w.message, HasSubstr("blocker/cache: cannot create the folder: Not a directory"));
    EXPECT_THAT(w.message, HasSubstr("the run goes on without storing in the cache"));
  }
  EXPECT_EQ(unwritable, 1);
  expect_same_outputs("plain", "blocked");
  // --strict makes the warning fail the run, as any other.
  options.strict = true;
  EXPECT_THROW(run_pipeline(config, options), Error);
}

TEST_F(CacheRun, AWriteThatFailsIsOneWarningWithTheReasonAndNothingStored) {
  run("plain", false);
  fs::create_directories(dir_ / "cache");
  std::ofstream(dir_ / "cache/synthesis") << "a file where the entries' folder should be\n";
  const RunReport report = run("failing");
  std::vector<std::string> messages;
  for (const Warning& w : report.warnings)
    if (w.code == "cache_unwritable") messages.push_back(w.message);
  ASSERT_EQ(messages.size(), 1u);  // the first failure; no store is tried after it
  EXPECT_THAT(messages[0],
              HasSubstr("cache: cannot create " + (dir_ / "cache/synthesis").string()));
  EXPECT_THAT(messages[0], HasSubstr("Not a directory"));  // the OS's reason, kept
  expect_same_outputs("plain", "failing");
  EXPECT_EQ(rebuilt("failing").size(), 5u);
}

// A killed run leaves its temporaries (.<entry>.twc.tmp<pid>-<n>) in whichever folder of the
// cache it was writing: the next run that finds no other using the cache (its lock free)
// removes them from every folder; one beside a run in progress keeps them.
TEST_F(CacheRun, TemporariesOfAKilledRunAreRemovedByTheNextRunAlone) {
  run("first");
  std::vector<fs::path> stale;
  for (const auto& entry : fs::recursive_directory_iterator(dir_ / "cache"))
    if (entry.is_directory())
      stale.push_back(entry.path() / (".0123abcd.twc.tmp4242-" + std::to_string(stale.size())));
  ASSERT_GE(stale.size(), 10u);  // synthesis, its last and inputs, tiles, plan stages...
  ASSERT_TRUE(fs::is_directory(dir_ / "cache/synthesis/inputs"));  // the finer check's index
  for (const fs::path& p : stale) {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << "half an entry";
  }
  std::ofstream(dir_ / "cache/synthesis/notes.txt") << "not a temporary";
  {
    // Another run holds the cache: nothing is swept under it.
    const int fd = ::open((dir_ / "cache/.lock").c_str(), O_RDWR | O_CREAT, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::flock(fd, LOCK_SH), 0);
    run("second");
    for (const fs::path& p : stale) EXPECT_TRUE(fs::exists(p)) << p;
    ::close(fd);
  }
  run("third");
  for (const fs::path& p : stale) EXPECT_FALSE(fs::exists(p)) << p;
  EXPECT_TRUE(fs::exists(dir_ / "cache/synthesis/notes.txt"));
  EXPECT_EQ(rebuilt("third"), std::set<int>{});  // the entries themselves kept
}

TEST_F(CacheRun, PipelineKeyNamesTheCacheRelativeToTheFile) {
  const std::string text = std::string(kCachePipeline) + "cache: kept\n";
  const PipelineConfig config =
      parse_pipeline(text, "cache.yaml", dir_.path(), {{"output.dir", (dir_ / "first").string()}});
  ASSERT_TRUE(config.cache_dir);
  EXPECT_EQ(*config.cache_dir, dir_ / "kept");
  run_pipeline(config);
  EXPECT_TRUE(fs::exists(dir_ / "kept/CACHEDIR.TAG"));
  EXPECT_EQ(rebuilt("first").size(), 5u);
  PipelineConfig again = config;
  again.output.dir = dir_ / "second";
  run_pipeline(again);
  EXPECT_EQ(rebuilt("second"), std::set<int>{});
  RunOptions elsewhere;  // --cache replaces the key: an empty cache rebuilds everything
  elsewhere.cache_dir = dir_ / "other";
  again.output.dir = dir_ / "third";
  run_pipeline(again, elsewhere);
  EXPECT_EQ(rebuilt("third").size(), 5u);
}

// --- Tiles as links (issue #23 item 2, docs/cache.md "Tile files are links") --------------------
constexpr const char* kTiled = "output: { tiles: { size: 80, overlap: 2 } }\n";

// Each tile's cache status as report.json lists it, by tile index.
std::vector<nlohmann::json> tile_statuses(const fs::path& out) {
  std::ifstream in(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);  // owned: the loop reads into it
  std::vector<nlohmann::json> statuses;
  for (const auto& t : report["tiles"]["tiles"]) statuses.push_back(t["cache"]);
  return statuses;
}

std::set<ino_t> inodes_under(const fs::path& dir) {
  std::set<ino_t> inodes;
  for (const auto& entry : fs::directory_iterator(dir)) {
    struct stat s {};
    if (::stat(entry.path().c_str(), &s) == 0) inodes.insert(s.st_ino);
  }
  return inodes;
}

// A reused tile's files are hard links to the cache's read-only files, not copies of them; the
// manifest's hashes (taken once, when a file is stored or checked) are a clean run's.
TEST_F(CacheRun, ReusedTileFilesAreReadOnlyLinksAndTheReportIsACleanRunsReport) {
  run("first", true, kTiled);
  run("second", true, kTiled);
  run("clean", false, kTiled);
  const std::vector<nlohmann::json> tiles = tile_statuses(dir_ / "second");
  ASSERT_EQ(tiles.size(), 4u);  // 80-pixel tiles of the 160-pixel world
  for (const auto& t : tiles) EXPECT_EQ(t["why"], "unchanged");
  expect_same_outputs("second", "clean");
  std::size_t values = 0, clean_values = 0;
  std::ifstream second(dir_ / "second/report.json"), clean(dir_ / "clean/report.json");
  const nlohmann::json cached = without_timings(nlohmann::json::parse(second), values);
  EXPECT_EQ(cached.dump(1), without_timings(nlohmann::json::parse(clean), clean_values).dump(1));
  EXPECT_GE(cached["outputs"].size(), 4u * 6u);  // their hashes compared

  const std::set<ino_t> kept = inodes_under(dir_ / "cache/tiles/files");
  std::size_t linked = 0;
  for (const auto& entry : fs::directory_iterator(dir_ / "second/tiles")) {
    struct stat s {};
    ASSERT_EQ(::stat(entry.path().c_str(), &s), 0);
    EXPECT_TRUE(kept.contains(s.st_ino)) << entry.path() << " is no link to a cache file";
    EXPECT_GE(s.st_nlink, 3u) << entry.path();  // first, second and the cache
    EXPECT_EQ(s.st_mode & 0222, 0u) << entry.path() << " is writable";
    ++linked;
  }
  EXPECT_EQ(linked, 4u * 6u);  // height, splat, avoidance as EXR and GeoTIFF per tile
}

// An output file edited in place (made writable first) edits the cache file it is linked to:
// the next run finds its hash changed, warns naming it, rebuilds that tile alone and writes a
// clean run's bytes; the run after reuses every tile again.
TEST_F(CacheRun, AnOutputEditedInPlaceNeverReachesALaterRun) {
  run("out", true, kTiled);
  run("clean", false, kTiled);
  const fs::path edited = dir_ / "out/tiles/height_x1_y0.exr";
  ASSERT_TRUE(fs::exists(edited));
  test::flip_byte_in_place(edited, 10);
  ASSERT_NE(test::read_file(edited), test::read_file(dir_ / "clean/tiles/height_x1_y0.exr"));
  const RunReport report = run("out", true, kTiled);
  int corrupt = 0;
  for (const Warning& w : report.warnings) {
    if (w.code != "cache_corrupt") continue;
    ++corrupt;
    EXPECT_THAT(w.message, HasSubstr("tiles/files/"));
    EXPECT_THAT(w.message, HasSubstr("content hash mismatch"));
  }
  EXPECT_EQ(corrupt, 1);
  const std::vector<nlohmann::json> tiles = tile_statuses(dir_ / "out");
  ASSERT_EQ(tiles.size(), 4u);
  for (std::size_t i = 0; i < tiles.size(); ++i)
    EXPECT_EQ(tiles[i]["why"], i == 1 ? "corrupt entry" : "unchanged") << "tile " << i;
  expect_same_outputs("out", "clean");
  run("again", true, kTiled);
  for (const auto& t : tile_statuses(dir_ / "again")) EXPECT_EQ(t["why"], "unchanged");
  expect_same_outputs("again", "clean");
}

// The tile cache's warnings are the run's: under --strict, a corrupt cache file fails the run
// before anything is committed (the folder keeps the previous run's files).
TEST_F(CacheRun, UnderStrictACorruptCacheFileFailsTheRunBeforeTheCommit) {
  run("out", true, kTiled);
  const fs::path edited = dir_ / "out/tiles/splat_x0_y0.exr";
  fs::permissions(edited, fs::perms::owner_write, fs::perm_options::add);
  {
    std::fstream file(edited, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(std::streamoff(fs::file_size(edited) - 10));
    file.put('\x7f');
    ASSERT_TRUE(file.good());
  }
  const std::string bytes = test::read_file(edited);
  const PipelineConfig config =
      parse_pipeline(std::string(kCachePipeline) + kTiled, "cache.yaml", dir_.path(),
                     {{"output.dir", (dir_ / "out").string()}});
  RunOptions options;
  options.cache_dir = dir_ / "cache";
  options.strict = true;
  try {
    run_pipeline(config, options);
    FAIL() << "a strict run with a corrupt cache file succeeded";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("strict: 1 warning"));
    EXPECT_THAT(e.what(), HasSubstr("tiles/files/"));
    EXPECT_THAT(e.what(), HasSubstr("content hash mismatch"));
  }
  EXPECT_EQ(test::read_file(edited), bytes);  // nothing committed
}

// A cache file pruned while its entry stays: the tiles that need it are rebuilt as "new",
// without a warning, and their files are a clean run's.
TEST_F(CacheRun, APrunedCacheFileRebuildsTheTilesThatNeedIt) {
  run("first", true, kTiled);
  run("clean", false, kTiled);
  struct stat s {};
  ASSERT_EQ(::stat((dir_ / "first/tiles/splat_x0_y1.tif").c_str(), &s), 0);
  std::size_t pruned = 0;
  for (const auto& entry : fs::directory_iterator(dir_ / "cache/tiles/files")) {
    struct stat c {};
    if (::stat(entry.path().c_str(), &c) == 0 && c.st_ino == s.st_ino)
      pruned += fs::remove(entry.path());
  }
  ASSERT_EQ(pruned, 1u);
  const RunReport report = run("second", true, kTiled);
  for (const Warning& w : report.warnings) EXPECT_NE(w.code, "cache_corrupt") << w.message;
  const std::vector<nlohmann::json> tiles = tile_statuses(dir_ / "second");
  ASSERT_EQ(tiles.size(), 4u);
  EXPECT_EQ(tiles[2]["status"], "rebuilt");  // tile x0 y1
  EXPECT_EQ(tiles[2]["why"], "new");
  for (const auto& t : tiles) EXPECT_TRUE(t["why"] == "new" || t["why"] == "unchanged") << t;
  expect_same_outputs("second", "clean");
}

// --- Plan stages (ribbons, terrain plan) in the cache: issue #23 item 2 -------------------------

// The entries of a plan stage: DIR/plan/<stage>/<key>.twc.
std::vector<fs::path> plan_stage_entries(const fs::path& cache, const std::string& stage) {
  std::vector<fs::path> entries;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(cache / "plan" / stage, ec))
    entries.push_back(e.path());
  std::sort(entries.begin(), entries.end());
  return entries;
}

// A rerun takes the ribbons and the terrain plan from the cache, not from the lines and the
// heights: a cached terrain plan whose profiles were raised by a metre (a valid entry under the
// same key) reaches the outputs. A new seed (the generated heights) keys a new terrain plan and
// keeps the ribbons; a moved road keys a new terrain plan and its own ribbon alone, and rewrites
// the latest junction search of each tolerance; each run's outputs are a clean run's.
TEST_F(CacheRun, PlanStagesAreReusedUnderTheirKeysAndRebuiltWhenTheirInputsChange) {
  run("first");
  const fs::path cache = dir_ / "cache";
  const std::vector<fs::path> terrain = plan_stage_entries(cache, "terrain");
  ASSERT_EQ(terrain.size(), 1u);
  const std::size_t ribbons = plan_stage_entries(cache, "ribbon").size();
  ASSERT_GE(ribbons, 4u);  // one per road long enough for pieces
  ASSERT_EQ(plan_stage_entries(cache, "junctions").size(), 2u);  // the pixel, the synthesis cell
  const std::size_t repairs = plan_stage_entries(cache, "repair").size();
  ASSERT_EQ(repairs, 5u);  // one per road's piece
  const detail::CacheRead read = detail::read_cache_entry(terrain[0]);
  ASSERT_EQ(read.state, detail::CacheRead::State::ok);
  detail::CacheSections raised = read.sections;
  TerrainPlan plan;
  detail::from_bytes(raised.at("value"), plan, "test");
  ASSERT_FALSE(plan.profiles.empty());
  for (auto& profile : plan.profiles)
    for (float& z : profile) z += 1.0f;
  raised["value"] = detail::to_bytes(plan);
  detail::write_cache_entry(terrain[0], raised);
  run("raised");
  EXPECT_EQ(plan_stage_entries(cache, "terrain"), terrain);  // the same key
  EXPECT_NE(output_files(dir_ / "raised").at("height.exr"),
            output_files(dir_ / "first").at("height.exr"));
  detail::write_cache_entry(terrain[0], read.sections);  // as computed

  run("seed6", true, "", {{"seed", "6"}});
  run("clean6", false, "", {{"seed", "6"}});
  expect_same_outputs("seed6", "clean6");
  EXPECT_EQ(plan_stage_entries(cache, "terrain").size(), 2u);
  EXPECT_EQ(plan_stage_entries(cache, "ribbon").size(), ribbons);

  write_roads(dir_ / "roads.gpkg", roads_with_r1_moved());
  run("moved");
  run("clean_moved", false);
  expect_same_outputs("moved", "clean_moved");
  EXPECT_EQ(plan_stage_entries(cache, "terrain").size(), 3u);
  EXPECT_EQ(plan_stage_entries(cache, "ribbon").size(), ribbons + 1);
  EXPECT_EQ(plan_stage_entries(cache, "junctions").size(), 2u);
  EXPECT_EQ(plan_stage_entries(cache, "repair").size(), repairs + 1);
}

// A corrupt plan-stage entry (here a feature's ribbon) is the warning cache_corrupt naming it, is
// rebuilt (a clean run's outputs) and is whole again for the next run.
TEST_F(CacheRun, ACorruptPlanStageEntryIsAWarningAndRebuilt) {
  run("first");
  const std::vector<fs::path> ribbons = plan_stage_entries(dir_ / "cache", "ribbon");
  ASSERT_FALSE(ribbons.empty());
  std::string bytes = test::read_file(ribbons[0]);
  bytes[bytes.size() / 2] ^= 0x20;
  fs::permissions(ribbons[0], fs::perms::owner_write, fs::perm_options::add);
  std::ofstream(ribbons[0], std::ios::binary | std::ios::trunc) << bytes;
  const RunReport report = run("second");
  int corrupt = 0;
  for (const Warning& w : report.warnings) {
    if (w.code != "cache_corrupt") continue;
    ++corrupt;
    EXPECT_EQ(w.subject, "plan.ribbon");
    EXPECT_THAT(w.message, HasSubstr(ribbons[0].filename().string()));
  }
  EXPECT_EQ(corrupt, 1);
  expect_same_outputs("first", "second");
  const RunReport third = run("third");
  for (const Warning& w : third.warnings) EXPECT_NE(w.code, "cache_corrupt") << w.message;
}

// The heights' identity in the terrain plan's key: a DEM's bytes (the same grid and nodata),
// a generated world's seed; the key also changes with the features and the parameters.
TEST(PlanStageCacheKey, HoldsTheHeightsTheFeaturesAndTheParameters) {
  test::TempDir dir;
  Heightfield grid_only;
  grid_only.grid = {64, 64, 500000.0, 5000640.0, 10.0, 10.0};
  detail::HeightfieldInput dem;
  dem.file = dir / "dem.tif";
  test::write_dem(*dem.file, {.nodata = -9999.0});
  const ContentHash slope = detail::heights_identity(dem, grid_only);
  EXPECT_EQ(detail::heights_identity(dem, grid_only), slope);
  test::write_dem(*dem.file, {.nodata = -9999.0, .all_nodata = true});
  EXPECT_NE(detail::heights_identity(dem, grid_only), slope);

  detail::HeightfieldInput generated;
  generated.seed = 5;
  const ContentHash seed5 = detail::heights_identity(generated, grid_only);
  generated.seed = 6;
  EXPECT_NE(detail::heights_identity(generated, grid_only), seed5);

  TerrainFeature road;
  road.kind = FeatureKind::road;
  road.centerline = {{{500100.0, 5000300.0}, {500500.0, 5000300.0}}, false};
  road.width = 6.0;
  const TerrainParams params;
  const ContentHash key = detail::terrain_plan_key(seed5, {road}, params);
  EXPECT_NE(detail::terrain_plan_key(slope, {road}, params), key);
  TerrainFeature moved = road;
  moved.centerline.points[1].y += 1.0;
  EXPECT_NE(detail::terrain_plan_key(seed5, {moved}, params), key);
  TerrainParams reordered;
  reordered.precedence = {FeatureKind::road, FeatureKind::river, FeatureKind::ridge};
  EXPECT_NE(detail::terrain_plan_key(seed5, {road}, reordered), key);
}

// A terrain plan rebuilt for a moved road reads the heights along that road alone: the others'
// samples come from the cache, the same values, and the entry keeps the latest centrelines.
TEST(PlanStageCacheKey, HeightsAlongAreSampledOnlyForCentrelinesNotSeenBefore) {
  test::TempDir dir;
  int calls = 0;
  const HeightsAlong sample = [&](const Curve& c, double step) {
    ++calls;
    return std::vector<double>{c.points[0].x, c.points[0].y, step};
  };
  const ContentHash heights = Hasher().text("some heights").digest();
  const Curve r1{{{0.0, 0.0}, {100.0, 0.0}}, false}, r2{{{0.0, 5.0}, {0.0, 90.0}}, false};
  Curve moved = r1;
  moved.points[0].y = 10.0;
  {
    detail::CachedHeightsAlong along(dir.path(), heights, sample);
    const HeightsAlong read = along.reader();
    EXPECT_EQ(read(r1, 2.0), (std::vector<double>{0.0, 0.0, 2.0}));
    read(r2, 2.0);
    EXPECT_EQ(along.sampled(), 2);
    along.store();
  }
  detail::CachedHeightsAlong along(dir.path(), heights, sample);
  const HeightsAlong read = along.reader();
  EXPECT_EQ(read(r2, 2.0), (std::vector<double>{0.0, 5.0, 2.0}));  // from the cache
  EXPECT_EQ(read(moved, 2.0), (std::vector<double>{0.0, 10.0, 2.0}));
  read(r2, 3.0);  // another step: sampled again
  EXPECT_EQ(along.sampled(), 2);
  EXPECT_EQ(calls, 4);
  along.store();
  detail::CachedHeightsAlong latest(dir.path(), heights, sample);
  latest.reader()(moved, 2.0);
  latest.reader()(r1, 2.0);  // not in the latest plan: dropped from the entry
  EXPECT_EQ(latest.sampled(), 1);
  detail::CachedHeightsAlong other(dir.path(), Hasher().text("other heights").digest(), sample);
  other.reader()(r2, 2.0);
  EXPECT_EQ(other.sampled(), 1);
  detail::CachedHeightsAlong none(std::nullopt, heights, sample);
  none.reader()(r2, 2.0);
  EXPECT_EQ(none.sampled(), 1);
}

}  // namespace
}  // namespace tw
