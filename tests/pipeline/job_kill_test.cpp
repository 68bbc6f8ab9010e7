// `complete-plan` and `finish` are crash-safe and idempotent (issue #24 item 3; the kill tests
// of the output folder itself are in output_folder_test.cpp). The real CLI is killed with
// SIGKILL just before its N-th file-system call that changes something (support/
// fault_injection.c, preloaded: no timing involved), for every N until it completes; after each
// kill the same command is run again and must succeed and leave the same bytes as one
// uninterrupted run (timings aside). A tiny world: two crossing cobbled roads, 2 x 2 tiles.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "test_world.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// report.json and plan.json without what differs between two runs of the same inputs.
json without_timings(json j) {
  if (j.is_object()) {
    json kept = json::object();
    for (auto& [key, value] : j.items())
      if (!key.ends_with("seconds") && key != "stages" && key != "started_utc" &&
          key != "timings" && key != "report_xxh3_128")
        kept[key] = without_timings(value);
    return kept;
  }
  if (j.is_array())
    for (json& item : j) item = without_timings(item);
  return j;
}

// Every file and folder under `root` (but the lock, which holds the pid), files by their bytes;
// JSON files with timings, and the manifest's run token, normalized.
std::map<std::string, std::string> snapshot(const fs::path& root) {
  std::map<std::string, std::string> entries;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator();
       ++it) {
    const std::string name = it->path().lexically_relative(root).generic_string();
    if (it->is_directory()) {
      entries[name + "/"] = "";
      continue;
    }
    if (name.ends_with(".terraweave/lock")) continue;
    std::string bytes = read_file(it->path());
    if (name.ends_with("report.json") || name.ends_with("plan/plan.json") ||
        name.ends_with("finished.json"))
      bytes = without_timings(json::parse(bytes)).dump(1);
    if (name.ends_with(".terraweave/outputs")) bytes = bytes.substr(bytes.find('\n'));
    entries[name] = bytes;
  }
  return entries;
}

class JobKill : public ::testing::Test {
 protected:
  void SetUp() override {
    write_layer(dir / "map.gpkg", "roads",
                {{"LINESTRING (500040 5000200, 500440 5000220)", 6.0},
                 {"LINESTRING (500240 5000020, 500250 5000380)", 6.0}});
    const fs::path exemplars = source_dir() / "samples/exemplars";
    crop_raster(exemplars / "cobble_edging_200x56.png", dir / "cobble.png", "PNG", 40, 56);
    crop_raster(exemplars / "cobble_edging_200x56_height.tif", dir / "cobble_height.tif", "GTiff",
                40, 56);
    std::ofstream(dir / "pipeline.yaml") << R"(version: 1
seed: 3
generate: { width: 48, height: 40, pixel_size: 10, relief: 40, origin: [500000, 5000400] }
output: { preview: false, exr: false, tiles: { size: 24, overlap: 2 } }
features:
  roads:
    source: map.gpkg
    layer: roads
    kind: road
    width: 6
    synthesis: { exemplar: cobble.png, width: 8, scale: 5, delta: 8 }
)";
  }
  CommandResult terraweave(const std::string& args, const std::string& env = "") const {
    return run_command("cd '" + dir.path().string() + "' && " + env + " '" +
                       terraweave_binary().string() + "' -q " + args + " 2>&1");
  }
  void must(const std::string& args) const {
    const CommandResult r = terraweave(args);
    ASSERT_EQ(r.exit_code, 0) << args << "\n" << r.output;
  }
  // Copies `from` over `to` (removed first): the state every kill starts from.
  static void restore(const fs::path& from, const fs::path& to) {
    fs::remove_all(to);
    fs::copy(from, to, fs::copy_options::recursive);
  }
  // Kills `command` before its N-th call for N = 1, 2, ... until it completes; after each kill
  // reruns it and compares `compared` with `expected`. Returns the number of kill points.
  int kill_at_every_call(const std::string& command, const fs::path& pristine,
                         const std::map<std::string, std::string>& expected,
                         const std::function<void(int)>& after_kill = {}) {
    const std::string preload = std::string("LD_PRELOAD='") + TW_FAULT_INJECTION_LIB +
                                "' ASAN_OPTIONS=verify_asan_link_order=0 TW_FAULT_UNDER='" +
                                dir.path().string() + "'";
    for (int n = 1; n < 1000; ++n) {
      restore(pristine, dir / "out");
      const CommandResult killed =
          terraweave(command, preload + " TW_FAULT_KILL_AT=" + std::to_string(n));
      if (killed.exit_code == 0) {  // past its last call
        EXPECT_EQ(snapshot(dir / "out"), expected) << command << " uninterrupted";
        return n - 1;
      }
      EXPECT_TRUE(killed.exit_code == 137 || killed.exit_code == -1)
          << command << " at " << n << ": " << killed.output;
      if (after_kill) after_kill(n);
      const CommandResult rerun = terraweave(command);
      std::cout << command << ": killed before call " << n << ", rerun "
                << (rerun.exit_code == 0 ? "ok" : "FAILED: " + rerun.output) << std::endl;
      EXPECT_EQ(rerun.exit_code, 0) << command << " after a kill at " << n << ":\n" << rerun.output;
      if (rerun.exit_code != 0) continue;
      const auto after = snapshot(dir / "out");
      EXPECT_EQ(after, expected) << command << " after a kill at " << n;
      // Nothing left beside the output folder (staging or previous folders).
      for (const auto& entry : fs::directory_iterator(dir.path()))
        EXPECT_FALSE(entry.path().filename().string().starts_with(".out."))
            << entry.path() << " left after a kill at " << n;
    }
    ADD_FAILURE() << command << " never completed";
    return 0;
  }
  TempDir dir;
};

TEST_F(JobKill, CompletePlanKilledAtEveryCallThenRerunGivesTheSamePlan) {
  must("plan pipeline.yaml --out out --synthesis tasks");
  must("synth-feature out --feature 0");
  must("synth-feature out --feature 1");
  fs::copy(dir / "out", dir / "pristine", fs::copy_options::recursive);
  must("complete-plan out");
  must("complete-plan out");  // idempotent: complete already
  const auto expected = snapshot(dir / "out");
  ASSERT_TRUE(expected.contains(".terraweave/plan/plan.json"));
  ASSERT_FALSE(expected.contains(".terraweave/plan/completing.json"));
  int journaled = 0;
  const int points =
      kill_at_every_call("complete-plan out", dir / "pristine", expected, [&](int n) {
        // Killed after its journal: the other commands say what to do, and that command works
        // (the rerun below); before, render-tile advised the very command that failed.
        if (!fs::exists(dir / "out/.terraweave/plan/completing.json")) return;
        ++journaled;
        const CommandResult tile = terraweave("render-tile out --tile 0");
        EXPECT_EQ(tile.exit_code, 1) << n;
        EXPECT_THAT(tile.output, ::testing::HasSubstr("complete-plan was interrupted"));
        EXPECT_THAT(tile.output, ::testing::HasSubstr("run it again: terraweave complete-plan"));
      });
  EXPECT_GT(journaled, 3);
  std::cout << "complete-plan: " << points << " kill points" << std::endl;
  EXPECT_GT(points, 5);
  // The completed plan renders: every task after it works.
  must("render-tile out --tile 0");
}

TEST_F(JobKill, FinishKilledAtEveryCallThenRerunGivesTheSameRun) {
  // One tile and no synthesis: finish's calls are per file (each tile file and each file of
  // the plan folder is linked into the new folder, the previous folder's deleted).
  must(
      "plan pipeline.yaml --out out --set output.tiles.size=48 --set "
      "features.roads.synthesis=null");
  must("render-tile out --tile 0");
  fs::copy(dir / "out", dir / "pristine", fs::copy_options::recursive);
  must("finish out");
  must("finish out");  // idempotent: finished already (a requeued job)
  const auto expected = snapshot(dir / "out");
  ASSERT_TRUE(expected.contains("report.json"));
  ASSERT_TRUE(expected.contains("tiles/height_x0_y0.tif"));
  const int points = kill_at_every_call("finish out", dir / "pristine", expected);
  std::cout << "finish: " << points << " kill points" << std::endl;
  EXPECT_GT(points, 10);
}

// render-tile ends with _Exit once its files are renamed and its result written (no static
// destructors, no joins of idle worker threads: src/cli/main.cpp): its line still reaches a
// redirected (fully buffered) stdout, its files and result are there and no temporary is left.
TEST_F(JobKill, RenderTileExitsAtOnceWithItsLinePrintedAndNoTemporaryLeft) {
  must(
      "plan pipeline.yaml --out out --set output.tiles.size=48 --set "
      "features.roads.synthesis=null");
  const CommandResult r =
      run_command("cd '" + dir.path().string() + "' && '" + terraweave_binary().string() +
                  "' -q render-tile out --tile 0 > tile.txt");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(read_file(dir / "tile.txt"),
              ::testing::MatchesRegex("tile 0: [1-9][0-9]* files in .* s\n"));
  int results = 0, tile_files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "out")) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".tmp-"), std::string::npos) << entry.path();
    results += name == "tile-0.json";
    tile_files += name.starts_with("height_x0_y0.");
  }
  EXPECT_EQ(results, 1);
  EXPECT_EQ(tile_files, 1);
}

}  // namespace
}  // namespace tw::test
