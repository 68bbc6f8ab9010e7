// The output folder guarantee (issue #9 item 7, docs/robustness.md): the real terraweave binary
// is killed with SIGKILL at every step of writing and committing a run (it pauses there through
// TERRAWEAVE_TEST_PAUSE_AT, so no timing is involved); after each kill a reader sees exactly
// the files of one complete run, the old or the new, and the next run deletes what was left.
// Two runs into one folder: the second fails at once naming the first, and writes nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "test_support.hpp"
#include "test_world.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::MatchesRegex;

// Run A writes EXR layers and a preview; run B (wider roads: other heights) EXR and GeoTIFF
// layers and no preview, so B adds names (the .tif) and drops one (preview.png).
const char* const kPipeline = R"(version: 1
seed: 1
heightfield: dem.tif
output: { dir: out, geotiff: false }
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 6 }
)";
const char* const kRunB =
    " --set output.geotiff=true --set output.preview=false"
    " --set features.roads.width=12";

// report.json without what changes from run to run (timings).
std::string report_without_timings(const std::string& text) {
  nlohmann::json json = nlohmann::json::parse(text);
  json.erase("stages");
  json.erase("total_seconds");
  for (auto& c : json["classes"]) c.erase("ingest_seconds");
  for (auto& t : json["tiles"]["tiles"]) t.erase("seconds");
  return json.dump();
}

// What a reader of the folder sees: every file reached by its name (through the links), but
// the user's notes and terraweave's own .terraweave folder.
using Outputs = std::map<std::string, std::string>;
Outputs visible_outputs(const fs::path& dir) {
  Outputs files;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator();
       ++it) {
    if (it->path().filename() == ".terraweave") {
      it.disable_recursion_pending();
      continue;
    }
    const std::string name = it->path().lexically_relative(dir).string();
    if (!it->is_regular_file() || name == "notes.txt") continue;
    files[name] = name == "report.json" ? report_without_timings(read_file(it->path()))
                                        : read_file(it->path());
  }
  return files;
}

// Every entry of the folder, links as their text (what a run that must write nothing keeps).
std::map<std::string, std::string> every_entry(const fs::path& dir) {
  std::map<std::string, std::string> entries;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = entry.path().lexically_relative(dir).string();
    if (entry.is_symlink()) {
      entries[name] = "-> " + fs::read_symlink(entry.path()).string();
    } else if (entry.is_regular_file()) {
      entries[name] = read_file(entry.path());
    } else {
      entries[name] = "folder";
    }
  }
  return entries;
}

// Links anywhere in the folder that resolve to nothing.
std::vector<std::string> dangling_links(const fs::path& dir) {
  std::vector<std::string> dangling;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_symlink() && !fs::exists(entry.path())) dangling.push_back(entry.path().string());
  }
  return dangling;
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

struct PausedRun {
  bool paused = false;  // it reached the point (and was killed there)
  int pid = 0;
  int exit_code = 0;  // of a run that did not pause
  std::string output;
};

// Runs `command` with TERRAWEAVE_TEST_PAUSE_AT=`point`; when it pauses there, calls
// `while_paused` and kills it with SIGKILL.
PausedRun run_paused_at(const std::string& command, const std::string& point,
                        const std::function<void()>& while_paused = {}) {
  PausedRun run;
  FILE* pipe = ::popen(
      ("export TERRAWEAVE_TEST_PAUSE_AT='" + point + "'; " + command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return run;
  const std::string marker = "terraweave: paused at " + point + " (pid ";
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), int(buffer.size()), pipe) != nullptr) {
    const std::string line = buffer.data();
    run.output += line;
    if (!run.paused && line.starts_with(marker)) {
      run.paused = true;
      run.pid = std::stoi(line.substr(marker.size()));
      if (while_paused) while_paused();
      ::kill(run.pid, SIGKILL);
    }
  }
  const int status = ::pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

class OutputFolderGuarantee : public ::testing::Test {
 protected:
  void SetUp() override {
    write_dem(dir / "dem.tif");
    write_layer(dir / "map.gpkg", "roads",
                {{"LINESTRING (500100 5000100, 500300 5000300, 500500 5000350)", 6.0}});
    std::ofstream(dir / "pipeline.yaml") << kPipeline;
  }

  std::string command(const std::string& out, const std::string& args = "") const {
    return "cd '" + dir.path().string() + "' && exec '" + terraweave_binary().string() +
           "' -q run pipeline.yaml --threads 1 --out " + out + args;
  }

  Outputs complete_run(const std::string& out, const std::string& args) {
    const CommandResult r = run_command(command(out, args));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return visible_outputs(dir / out);
  }

  TempDir dir;
};

TEST_F(OutputFolderGuarantee, AKilledRunLeavesOneCompleteRunAndTheNextCleansUp) {
  const Outputs a = complete_run("a", "");
  const Outputs b = complete_run("b", kRunB);
  ASSERT_TRUE(a.contains("preview.png") && !a.contains("height.tif")) << a.size();
  ASSERT_TRUE(b.contains("height.tif") && !b.contains("preview.png")) << b.size();
  ASSERT_NE(a.at("height.exr"), b.at("height.exr"));
  // The old state: run A in a folder that also holds the user's notes.
  fs::create_directories(dir / "old");
  std::ofstream(dir / "old/notes.txt") << "kept";
  ASSERT_EQ(complete_run("old", ""), a);

  // Points before the commit (files being written), then every step of it until the run ends.
  std::vector<std::string> points = {"stage:3"};
  int old_seen = 0, new_seen = 0, completed = 0;
  for (std::size_t i = 0; completed == 0 && i < 30; ++i) {
    if (i >= points.size()) points.push_back("commit:" + std::to_string(i - 1));
    const std::string point = points[i];
    SCOPED_TRACE(point);
    fs::remove_all(dir / "out");
    fs::copy(dir / "old", dir / "out",
             fs::copy_options::recursive | fs::copy_options::copy_symlinks);
    const PausedRun killed = run_paused_at(command("out", kRunB), point);
    if (!killed.paused) {  // past the last step: the run completed
      EXPECT_EQ(killed.exit_code, 0) << killed.output;
      EXPECT_EQ(visible_outputs(dir / "out"), b);
      ++completed;
      continue;
    }
    const Outputs seen = visible_outputs(dir / "out");
    EXPECT_TRUE(seen == a || seen == b) << seen.size() << " files, a mix of runs";
    old_seen += seen == a;
    new_seen += seen == b;
    if (point.starts_with("stage:") || point == "commit:0") {
      EXPECT_EQ(seen, a);
    }
    EXPECT_EQ(read_file(dir / "out/notes.txt"), "kept");

    // The next run deletes the staging folder, old generations and links of a dead run (once
    // per kind of leftover: the 2nd and 3rd new links leave what the 1st does).
    if (point == "commit:3" || point == "commit:4") continue;
    EXPECT_EQ(complete_run("out", kRunB), b);
    EXPECT_EQ(names_in(dir / "out/.terraweave"),
              (std::vector<std::string>{
                  "current", fs::read_symlink(dir / "out/.terraweave/current"), "lock"}));
    EXPECT_THAT(dangling_links(dir / "out"), ::testing::IsEmpty());
    EXPECT_EQ(read_file(dir / "out/notes.txt"), "kept");
  }
  EXPECT_EQ(completed, 1);
  // Old until the swap: staging, commit:0, 1 (generation renamed), 2-4 (the 3 new .tif links
  // made); new after it: commit:5 (swapped) and commit:6 (the old run deleted).
  EXPECT_EQ(old_seen, 6);
  EXPECT_EQ(new_seen, 2);
  EXPECT_EQ(points.back(), "commit:7");
}

// A run replaces the outputs of the previous one as a whole: names it does not write vanish.
TEST_F(OutputFolderGuarantee, OutputsTheNewRunDoesNotWriteDisappear) {
  fs::create_directories(dir / "out");
  std::ofstream(dir / "out/notes.txt") << "kept";
  // Temporaries of an older terraweave: of a dead process (deleted) and of a live one (kept).
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const std::string dead_temporary = ".height.tmp" + std::to_string(dead) + ".exr";
  const std::string live_temporary = ".height.tmp" + std::to_string(::getpid()) + ".exr";
  std::ofstream(dir / "out" / dead_temporary) << "half";
  std::ofstream(dir / "out" / live_temporary) << "being written";
  const std::string users_file = ".notes.tmp" + std::to_string(dead) + ".exr";  // not an output
  std::ofstream(dir / "out" / users_file) << "mine";
  complete_run("out", "");
  EXPECT_FALSE(fs::exists(dir / "out" / dead_temporary));
  EXPECT_TRUE(fs::remove(dir / "out" / live_temporary));  // they were still there
  EXPECT_TRUE(fs::remove(dir / "out" / users_file));
  const Outputs b = complete_run("out", kRunB);
  EXPECT_FALSE(b.contains("preview.png"));
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "out/preview.png")));  // not even a link
  EXPECT_EQ(names_in(dir / "out"),
            (std::vector<std::string>{".terraweave", "avoidance.exr", "avoidance.tif", "height.exr",
                                      "height.tif", "notes.txt", "report.json", "splat.exr",
                                      "splat.tif"}));
  EXPECT_EQ(fs::read_symlink(dir / "out/.terraweave/current"), "gen-2");
}

TEST_F(OutputFolderGuarantee, ASecondRunFailsAtOnceNamingTheFirstAndWritesNothing) {
  fs::create_directories(dir / "out");
  std::ofstream(dir / "out/notes.txt") << "kept";
  std::map<std::string, std::string> before_second;
  CommandResult second;
  const PausedRun first = run_paused_at(command("out"), "lock", [&] {
    before_second = every_entry(dir / "out");
    second = run_command(command("out", kRunB));
  });
  ASSERT_TRUE(first.paused) << first.output;
  EXPECT_EQ(second.exit_code, 1) << second.output;
  EXPECT_THAT(second.output,
              MatchesRegex("terraweave: error: output folder out is in use by another terraweave "
                           "run \\(pid " +
                           std::to_string(first.pid) +
                           ", started [0-9-]+ [0-9:]+ UTC\\); wait for it to finish or choose "
                           "another --out\n"));
  EXPECT_EQ(every_entry(dir / "out"), before_second);
  // Once the first is gone (killed), the folder is free again.
  const Outputs b = complete_run("out", kRunB);
  EXPECT_TRUE(b.contains("height.tif"));
  EXPECT_THAT(dangling_links(dir / "out"), ::testing::IsEmpty());
}

}  // namespace
}  // namespace tw::test
