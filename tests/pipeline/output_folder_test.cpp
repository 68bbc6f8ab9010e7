// The output folder guarantee (issue #9 item 7, issue #22 item 1, docs/robustness.md): the real
// terraweave binary is killed with SIGKILL at every step of writing and committing a run (it
// pauses there through TERRAWEAVE_TEST_PAUSE_AT, so no timing is involved); after each kill a
// reader sees exactly the files of one complete run, the old or the new, and the next run
// deletes what was left. The same for the fallback without RENAME_EXCHANGE and for the commit
// in place. The folder holds plain files only (cp -r and tar copy it as it is); a reader during
// commits sees one run; a folder of the older layout (links) is migrated. Two runs into one
// folder: the second fails at once naming the first, and writes nothing.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

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
  json.erase("timings");
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

// Every entry under the folder that is not a plain file or folder (a link, above all).
std::vector<std::string> not_plain(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const fs::file_type type = entry.symlink_status().type();
    if (type != fs::file_type::regular && type != fs::file_type::directory)
      found.push_back(entry.path().string());
  }
  return found;
}

// What the folder's commits leave beside it: .<name>.terraweave-* (none once a run is over).
std::vector<std::string> siblings_of(const fs::path& dir) {
  std::vector<std::string> found;
  const std::string prefix = "." + dir.filename().string() + ".terraweave-";
  for (const auto& entry : fs::directory_iterator(dir.parent_path()))
    if (entry.path().filename().string().starts_with(prefix))
      found.push_back(entry.path().filename());
  return found;
}

ino_t inode_of(const fs::path& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 ? st.st_ino : 0;
}

// Whether every file seen is the one run `run` wrote under that name (a part of it, or all).
bool is_part_of(const Outputs& seen, const Outputs& run) {
  for (const auto& [name, bytes] : seen) {
    const auto it = run.find(name);
    if (it == run.end() || it->second != bytes) return false;
  }
  return true;
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

  // Run A with the user's notes in "old"; run B alone in "b" (what the folder must become).
  void two_runs() {
    a = complete_run("a", "");
    b = complete_run("b", kRunB);
    ASSERT_TRUE(a.contains("preview.png") && !a.contains("height.tif")) << a.size();
    ASSERT_TRUE(b.contains("height.tif") && !b.contains("preview.png")) << b.size();
    ASSERT_NE(a.at("height.exr"), b.at("height.exr"));
    fs::create_directories(dir / "old");
    std::ofstream(dir / "old/notes.txt") << "kept";
    ASSERT_EQ(complete_run("old", ""), a);
  }

  // After the commits of one run are over: only the user's notes, the outputs and
  // .terraweave/{lock,outputs}, all plain files, nothing left beside the folder.
  void expect_clean(const fs::path& out) {
    EXPECT_EQ(names_in(out / ".terraweave"), (std::vector<std::string>{"lock", "outputs"}));
    EXPECT_THAT(not_plain(out), ::testing::IsEmpty());
    EXPECT_THAT(siblings_of(out), ::testing::IsEmpty());
    EXPECT_EQ(read_file(out / "notes.txt"), "kept");
  }

  Outputs a, b;

  TempDir dir;
};

TEST_F(OutputFolderGuarantee, AKilledRunLeavesOneCompleteRunAndTheNextCleansUp) {
  two_runs();
  // Points before the commit (files being written), then every step of it until the run ends.
  std::vector<std::string> points = {"stage:3"};
  int old_seen = 0, new_seen = 0, completed = 0;
  for (std::size_t i = 0; completed == 0 && i < 30; ++i) {
    if (i >= points.size()) points.push_back("commit:" + std::to_string(i - 1));
    const std::string point = points[i];
    SCOPED_TRACE(point);
    fs::remove_all(dir / "out");
    fs::copy(dir / "old", dir / "out", fs::copy_options::recursive);
    const ino_t lock = inode_of(dir / "out/.terraweave/lock");
    const PausedRun killed = run_paused_at(command("out", kRunB), point);
    if (!killed.paused) {  // past the last step: the run completed
      EXPECT_EQ(killed.exit_code, 0) << killed.output;
      EXPECT_EQ(visible_outputs(dir / "out"), b);
      expect_clean(dir / "out");
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
    EXPECT_THAT(not_plain(dir / "out"), ::testing::IsEmpty());

    // Swapped, not yet deleted: the previous folder beside. A file the user made there in the
    // moment between the carrying of their files and the swap is moved to the folder.
    const std::vector<std::string> beside = siblings_of(dir / "out");
    if (point == "commit:2") {
      EXPECT_EQ(seen, b);
      ASSERT_EQ(beside.size(), 1u);
      std::ofstream(dir / beside[0] / "late.txt") << "late";
    }
    // The next run deletes the staging folder or the previous folder a dead run left beside.
    complete_run("out", kRunB);
    if (point == "commit:2") {
      EXPECT_EQ(read_file(dir / "out/late.txt"), "late");
      fs::remove(dir / "out/late.txt");
    }
    EXPECT_EQ(visible_outputs(dir / "out"), b);
    expect_clean(dir / "out");
    // Every folder swapped in holds the same lock file (a second run would see it held).
    EXPECT_EQ(inode_of(dir / "out/.terraweave/lock"), lock);
  }
  EXPECT_EQ(completed, 1);
  // Old until the swap: staging, commit:0, commit:1 (complete beside the folder); new after it:
  // commit:2 (swapped) and commit:3 (the previous folder deleted).
  EXPECT_EQ(old_seen, 3);
  EXPECT_EQ(new_seen, 2);
  EXPECT_EQ(points.back(), "commit:4");
}

// Without RENAME_EXCHANGE (NFS): two renames. Killed between them, the folder is absent, never
// mixed; the next command on it puts the complete new run in place before anything else.
TEST_F(OutputFolderGuarantee, WithoutExchangeAKilledRunLeavesNoFolderOrOneRun) {
  two_runs();
  const std::string no_exchange = " && export TERRAWEAVE_TEST_NO_EXCHANGE=1";
  std::vector<std::string> seen_per_point;
  for (int step = 0; step < 10; ++step) {
    const std::string point = "commit:" + std::to_string(step);
    SCOPED_TRACE(point);
    fs::remove_all(dir / "out");
    fs::copy(dir / "old", dir / "out", fs::copy_options::recursive);
    const std::string cmd = "cd '" + dir.path().string() + "'" + no_exchange + " && exec '" +
                            terraweave_binary().string() +
                            "' -q run pipeline.yaml --threads 1 --out out" + kRunB;
    const PausedRun killed = run_paused_at(cmd, point);
    if (!killed.paused) {
      EXPECT_EQ(killed.exit_code, 0) << killed.output;
      EXPECT_EQ(visible_outputs(dir / "out"), b);
      expect_clean(dir / "out");
      break;
    }
    if (!fs::exists(dir / "out")) {
      seen_per_point.push_back("none");
      // The next command locking the folder (here run A, stopped once it holds the lock) first
      // puts the complete new run in place.
      const PausedRun next = run_paused_at(command("out"), "lock");
      ASSERT_TRUE(next.paused) << next.output;
      EXPECT_EQ(visible_outputs(dir / "out"), b);
    } else {
      const Outputs seen = visible_outputs(dir / "out");
      EXPECT_TRUE(seen == a || seen == b) << seen.size() << " files, a mix of runs";
      seen_per_point.push_back(seen == a ? "a" : seen == b ? "b" : "mix");
    }
    EXPECT_EQ(complete_run("out", kRunB), b);
    expect_clean(dir / "out");
  }
  EXPECT_EQ(seen_per_point, (std::vector<std::string>{"a", "a", "none", "b", "b"}));
}

// A folder that cannot be swapped (here the current folder of the run) is committed in place:
// each file old or new; after a kill the next command completes the commit.
TEST_F(OutputFolderGuarantee, InPlaceACommitKilledIsCompletedByTheNextCommand) {
  two_runs();
  const auto in_folder = [&](const std::string& folder) {
    return "cd '" + (dir / folder).string() + "' && exec '" + terraweave_binary().string() +
           "' -q run ../pipeline.yaml --threads 1 --out ." + kRunB;
  };
  // Run B from inside its folder (report.json names the pipeline ../pipeline.yaml).
  fs::create_directories(dir / "b-in-place");
  ASSERT_EQ(run_command(in_folder("b-in-place")).exit_code, 0);
  const Outputs b_in_place = visible_outputs(dir / "b-in-place");
  ASSERT_EQ(b_in_place.size(), b.size());
  int mixed = 0;
  for (int step = 0; step < 30; ++step) {
    const std::string point = "commit:" + std::to_string(step);
    SCOPED_TRACE(point);
    fs::remove_all(dir / "out");
    fs::copy(dir / "old", dir / "out", fs::copy_options::recursive);
    const PausedRun killed = run_paused_at(in_folder("out"), point);
    if (!killed.paused) {
      EXPECT_EQ(killed.exit_code, 0) << killed.output;
      EXPECT_EQ(visible_outputs(dir / "out"), b_in_place);
      expect_clean(dir / "out");
      EXPECT_GT(step, 4);  // commit:3.. : one file renamed each
      break;
    }
    // Each file is the old run's or the new run's, whole.
    const Outputs seen = visible_outputs(dir / "out");
    for (const auto& [name, bytes] : seen) {
      const bool old_file = a.contains(name) && a.at(name) == bytes;
      const bool new_file = b_in_place.contains(name) && b_in_place.at(name) == bytes;
      EXPECT_TRUE(old_file || new_file) << name;
    }
    mixed += seen != a && seen != b_in_place;
    EXPECT_EQ(read_file(dir / "out/notes.txt"), "kept");
    // The next command that locks the folder completes the commit first.
    const PausedRun next = run_paused_at(command("out"), "lock");
    ASSERT_TRUE(next.paused) << next.output;
    const Outputs after = visible_outputs(dir / "out");
    EXPECT_TRUE(after == a || after == b_in_place) << after.size() << " files";
    if (step >= 2) {
      EXPECT_TRUE(after == b_in_place);  // commit-<token> was complete: rolled forward
    }
    EXPECT_TRUE(complete_run("out", kRunB) == b);
    expect_clean(dir / "out");
  }
  EXPECT_GT(mixed, 0);  // the weaker promise of the in-place commit, as documented
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
  fs::create_directories(dir / "out/qgis/styles");
  std::ofstream(dir / "out/qgis/styles/roads.qml") << "<qgis/>";
  complete_run("out", "");
  EXPECT_FALSE(fs::exists(dir / "out" / dead_temporary));
  EXPECT_TRUE(fs::remove(dir / "out" / live_temporary));  // they were still there
  EXPECT_TRUE(fs::remove(dir / "out" / users_file));
  const Outputs b = complete_run("out", kRunB);
  EXPECT_FALSE(b.contains("preview.png"));
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "out/preview.png")));
  EXPECT_EQ(names_in(dir / "out"),
            (std::vector<std::string>{".terraweave", "avoidance.exr", "avoidance.tif",
                                      "features.geojson", "height.exr", "height.tif", "notes.txt",
                                      "qgis", "report.json", "splat.exr", "splat.tif"}));
  EXPECT_EQ(read_file(dir / "out/qgis/styles/roads.qml"), "<qgis/>");
  expect_clean(dir / "out");
}

// What cp -r, tar (and so rsync, git, Perforce, a zip) make of a run and an export: the same
// plain files, no link anywhere.
TEST_F(OutputFolderGuarantee, CopiesAndArchivesHoldThePlainFiles) {
  const Outputs a = complete_run("out", kRunB);  // with GeoTIFFs, which export reads
  ASSERT_EQ(run_command("cd '" + dir.path().string() + "' && '" + terraweave_binary().string() +
                        "' -q export out --to unreal --out out-ue")
                .exit_code,
            0);
  for (const char* folder : {"out", "out-ue"})
    EXPECT_THAT(not_plain(dir / folder), ::testing::IsEmpty());
  const CommandResult copied = run_command(
      "cd '" + dir.path().string() +
      "' && cp -r out copy && mkdir untarred && tar cf out.tar out out-ue && tar xf out.tar -C "
      "untarred && find copy untarred ! -type f ! -type d | wc -l");
  ASSERT_EQ(copied.exit_code, 0) << copied.output;
  EXPECT_EQ(copied.output, "0\n");  // no link, no other kind of entry
  EXPECT_EQ(visible_outputs(dir / "copy"), a);
  EXPECT_EQ(visible_outputs(dir / "untarred/out"), a);
  EXPECT_EQ(visible_outputs(dir / "untarred/out-ue"), visible_outputs(dir / "out-ue"));
  EXPECT_FALSE(visible_outputs(dir / "out-ue").empty());
  // A run into the copy replaces the copied outputs as it would the original's.
  EXPECT_TRUE(complete_run("copy", "") == complete_run("b", ""));
}

// A reader that opens the folder once (a descriptor: cd, or openat) and reads every file
// through it, again and again while runs A and B replace each other: every read is one run.
TEST_F(OutputFolderGuarantee, AReaderDuringCommitsSeesOneRunNeverAMix) {
  const Outputs a = complete_run("a", "");
  const Outputs b = complete_run("b", kRunB);
  complete_run("out", "");
  std::atomic<bool> done{false};
  int complete_a = 0, complete_b = 0, partial = 0, mixed = 0;
  std::thread reader([&] {
    while (!done) {
      const int fd = ::open((dir / "out").c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      if (fd < 0) continue;
      // /proc/self/fd/<fd> names the folder opened, wherever the commit moves it.
      const fs::path opened = "/proc/self/fd/" + std::to_string(fd);
      Outputs seen;
      std::error_code ec;
      for (auto it = fs::recursive_directory_iterator(opened, ec);
           !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (it->path().filename() == ".terraweave") {
          it.disable_recursion_pending();
          continue;
        }
        std::error_code entry_ec;
        if (!it->is_regular_file(entry_ec)) continue;
        const std::string name = it->path().lexically_relative(opened).string();
        std::string bytes = read_file(it->path());
        // Deleted between the listing and the read (the previous folder going): not seen. The
        // check comes before report.json is parsed, or its empty read would count as a mix.
        if (bytes.empty() && !fs::exists(it->path())) continue;
        if (name == "report.json") {
          try {
            bytes = report_without_timings(bytes);
          } catch (const std::exception&) {
            bytes = "unreadable";  // neither run's report: a mix
          }
        }
        seen[name] = bytes;
      }
      ::close(fd);
      if (seen == a) {
        ++complete_a;
      } else if (seen == b) {
        ++complete_b;
      } else if (is_part_of(seen, a) || is_part_of(seen, b)) {
        ++partial;  // read while the previous folder was being deleted
      } else {
        ++mixed;
        std::string names;
        for (const auto& [name, bytes] : seen)
          names += " " + name + (a.contains(name) && a.at(name) == bytes   ? "(A)"
                                 : b.contains(name) && b.at(name) == bytes ? "(B)"
                                                                           : "(?)");
        std::printf("mixed read:%s\n", names.c_str());
      }
    }
  });
  for (int i = 0; i < 6; ++i)
    EXPECT_EQ(complete_run("out", i % 2 == 0 ? kRunB : ""), i % 2 == 0 ? b : a);
  done = true;
  reader.join();
  EXPECT_EQ(mixed, 0);
  EXPECT_GT(complete_a, 0);
  EXPECT_GT(complete_b, 0);
  std::printf("reader: %d reads of run A, %d of run B, %d partial (folder being deleted)\n",
              complete_a, complete_b, partial);
}

// A folder of the older layout (outputs as links into .terraweave/current) is migrated once, by
// the first command that locks it: plain files with the same bytes, the generations gone.
TEST_F(OutputFolderGuarantee, AFolderOfTheOlderLayoutIsMigrated) {
  const Outputs a = complete_run("a", "");
  const Outputs b = complete_run("b", kRunB);
  const fs::path legacy = dir / "legacy";
  fs::create_directories(legacy / ".terraweave/gen-1");
  fs::create_directories(legacy / ".terraweave/gen-2");
  for (const auto& entry : fs::recursive_directory_iterator(dir / "a")) {
    const fs::path name = entry.path().lexically_relative(dir / "a");
    if (*name.begin() == ".terraweave" || !entry.is_regular_file()) continue;
    fs::create_directories((legacy / ".terraweave/gen-2" / name).parent_path());
    fs::copy_file(entry.path(), legacy / ".terraweave/gen-2" / name);
    fs::path target;
    for (const auto& part : name.parent_path())
      if (!part.empty()) target /= "..";
    fs::create_symlink(target / ".terraweave/current" / name, legacy / name);
  }
  fs::create_symlink("gen-2", legacy / ".terraweave/current");
  fs::create_symlink(".terraweave/current/gone.tif", legacy / "gone.tif");  // of an older run
  std::ofstream(legacy / ".terraweave/gen-1/gone.tif") << "old";
  std::ofstream(legacy / ".terraweave/lock") << "pid 1, started 2026-01-01 00:00:00 UTC\n";
  std::ofstream(legacy / "notes.txt") << "kept";
  ASSERT_EQ(visible_outputs(legacy), a);  // read through the links

  const PausedRun locked = run_paused_at(command("legacy", kRunB), "lock");
  ASSERT_TRUE(locked.paused) << locked.output;
  EXPECT_EQ(visible_outputs(legacy), a);  // the same files, now plain
  expect_clean(legacy);
  EXPECT_EQ(complete_run("legacy", kRunB), b);
  expect_clean(legacy);
  EXPECT_FALSE(fs::exists(legacy / "preview.png"));  // an output of A, not of B
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
  expect_clean(dir / "out");
}

}  // namespace
}  // namespace tw::test
