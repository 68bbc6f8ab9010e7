// The bad-input corpus (issue #24, "Benchmarks to report"): several hundred bad inputs over every
// command, generated from tables (every numeric option × nan/inf/1e400/abc/-1..., every file
// option × missing/a folder//dev/null/non-UTF-8/empty, every pipeline key × wrong type/out of
// range/unknown, every run and plan file × truncated/not JSON/wrong types). Each must end in
// one clean error: non-zero exit, no signal, the last stderr line "terraweave: error: ..." (or
// "usage error"), that line naming the option, key, file or FID, and nothing written. The
// summary by outcome class is printed (docs/cli.md, "Errors").
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "test_support.hpp"
#include "test_world.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;

const char* const kPipeline = R"(version: 1
seed: 1
heightfield: dem.tif
output: { dir: out, preview: false }
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 6 }
)";

struct Case {
  std::string args;     // after `terraweave -q`, run in the corpus folder
  std::string expect;   // the error line names it
  std::string prepare;  // shell commands run first (a corrupted copy of a run or plan)
};

// A shell word.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (const char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

// Every file under `dir` with its size and time: what a case must leave as it was.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator();
       ++it) {
    std::error_code ec;
    const auto size = it->is_regular_file(ec) ? it->file_size(ec) : 0;
    files[fs::relative(it->path(), dir).string()] =
        std::to_string(size) + "@" +
        std::to_string(fs::last_write_time(it->path(), ec).time_since_epoch().count());
  }
  return files;
}

// Options that take a number: the values each must refuse.
struct NumericOption {
  std::string command;  // with every other required argument, valid
  std::string option;
  enum Kind { positive, any_real, count, seed } kind;
};

std::vector<std::string> bad_values(NumericOption::Kind kind) {
  switch (kind) {
    case NumericOption::positive:
      return {"nan", "inf", "-inf", "1e400", "abc", "-1", "''", "1,5", "0x"};
    case NumericOption::any_real:
      return {"nan", "inf", "-inf", "1e400", "abc", "''", "1,5"};
    case NumericOption::count:
      return {"abc", "1.5", "-1", "1e400", "99999999999999999999", "''", "nan"};
    case NumericOption::seed:
      return {"abc", "1.5", "1e400", "99999999999999999999", "''", "nan"};
  }
  return {};
}

class BadInputCorpus : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    const fs::path& d = dir_->path();
    write_dem(d / "dem.tif");
    write_layer(d / "map.gpkg", "roads",
                {{"LINESTRING (500100 5000100, 500300 5000300, 500500 5000350)", 6.0}});
    std::ofstream(d / "pipeline.yaml") << kPipeline;
    fs::create_directory(d / "adir");
    std::ofstream(d / "empty.txt");
    std::ofstream(d / "latin1.txt") << "h\xf6he: \xe9\xff\xfe\n";
    std::ofstream(d / "garbage.json") << "{\"format\": ";
    const std::string bin = "cd " + quoted(d.string()) + " && " + terraweave_binary().string();
    const CommandResult run = run_command(bin + " -q run pipeline.yaml --out run1");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const CommandResult tiled = run_command(
        bin + " -q run pipeline.yaml --out tiled1 --set 'output.tiles={size: 24, overlap: 2}'");
    ASSERT_EQ(tiled.exit_code, 0) << tiled.output;
    const CommandResult plan = run_command(
        bin + " -q plan pipeline.yaml --out plan1 --set 'output.tiles={size: 24, overlap: 2}'");
    ASSERT_EQ(plan.exit_code, 0) << plan.output;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }

  static std::vector<Case> corpus();

  static TempDir* dir_;
};

TempDir* BadInputCorpus::dir_ = nullptr;

std::vector<Case> BadInputCorpus::corpus() {
  const std::string samples = (source_dir() / "samples").string();
  const std::string exemplar = samples + "/exemplars/chain_199x82.png";
  const std::string synth = "synth --exemplar " + exemplar +
                            " --curve line --length 12 --width 4 --delta 3 --scale 4 "
                            "--backend cpu -o @o/s.png";
  const std::string area = "area " + samples + "/sketches/vineyard.geojson --polygons " + samples +
                           "/map.gpkg:existing --scale 40 --out @o";
  const std::string grow = "grow --dem " + samples +
                           "/dem.tif --region 291200,9115100,291500,"
                           "9115400 --element " +
                           samples +
                           "/ornaments/hedge.json --resolution "
                           "10 --max-ornaments 4 --out @o";
  const std::string network = "network synthesize --exemplar " + samples +
                              "/map.gpkg:roads "
                              "--region 290000,9112000,296000,9118000 --out @o";
  std::vector<Case> cases;

  // 1. Numeric options: the value replaces a valid one given earlier on the line (CLI11 keeps
  //    the last) or is added.
  const std::vector<NumericOption> numeric = {
      {"run pipeline.yaml --out @o", "--threads", NumericOption::count},
      {synth, "--length", NumericOption::positive},
      {synth, "--width", NumericOption::positive},
      {synth, "--delta", NumericOption::positive},
      {synth, "--scale", NumericOption::positive},
      {synth, "--min-coverage", NumericOption::positive},
      {synth, "--coverage-weight", NumericOption::positive},
      {synth, "--feather", NumericOption::positive},
      {synth, "--seed", NumericOption::seed},
      {area, "--scale", NumericOption::positive},
      {area, "--bearing", NumericOption::any_real},
      {area, "--seed", NumericOption::seed},
      {area, "--jitter", NumericOption::positive},
      {area, "--avoid-width", NumericOption::positive},
      {area, "--resolution", NumericOption::positive},
      {grow, "--resolution", NumericOption::positive},
      {grow, "--seed", NumericOption::seed},
      {grow, "--trials", NumericOption::count},
      {grow, "--max-ornaments", NumericOption::count},
      {grow, "--clearance", NumericOption::positive},
      {grow, "--coverage-radius", NumericOption::positive},
      {grow, "--avoid-width", NumericOption::positive},
      {network, "--avoid-width", NumericOption::positive},
      {network, "--seed", NumericOption::seed},
      {network, "--lead-bearing", NumericOption::any_real},
      {network, "--clearance", NumericOption::positive},
      {network, "--snap", NumericOption::positive},
      {network, "--candidates", NumericOption::count},
      {"synth-feature plan1", "--feature", NumericOption::count},
      {"render-tile plan1", "--tile", NumericOption::count},
      {"export run1 --to godot --out @o", "--tile-size", NumericOption::count},
      {"export run1 --to godot --out @o", "--nodata-height", NumericOption::any_real},
  };
  for (const NumericOption& o : numeric)
    for (const std::string& v : bad_values(o.kind))
      cases.push_back({o.command + " " + o.option + " " + v, o.option, ""});

  // 2. File arguments: missing, a folder, /dev/null, a non-UTF-8 text, an empty file, JSON
  //    cut short. Each error names the file.
  const std::vector<std::pair<std::string, std::string>> file_options = {
      {"run {}", ""},
      {"validate {}", ""},
      {"plan {} --out @o", ""},
      {"synth --curve line --length 12 --width 4 --delta 3 --scale 4 -o @o/s.png --exemplar {}",
       ""},
      {"synth --exemplar " + exemplar + " --width 4 --delta 3 --scale 4 -o @o/s.png --curve {}",
       ""},
      {"area {} --polygons " + samples + "/map.gpkg:existing --scale 40 --out @o", ""},
      {"area " + samples + "/sketches/vineyard.geojson --scale 40 --out @o --polygons {}", ""},
      {"grow --region 291200,9115100,291500,9115400 --element " + samples +
           "/ornaments/hedge.json --out @o --dem {}",
       ""},
      {"grow --dem " + samples +
           "/dem.tif --region 291200,9115100,291500,9115400 --out @o "
           "--element {}",
       ""},
      {"network synthesize --region 290000,9112000,296000,9118000 --out @o --exemplar {}", ""},
      {"exemplar inspect {}", ""},
      {"export --to godot --out @o {}", ""},
      {"view --out @o/v.html {}", ""},
      {"diff run1 {}", ""},
      {"diff {} run1", ""},
      {"synth-feature --feature 0 {}", ""},
      {"complete-plan {}", ""},
      {"render-tile --tile 0 {}", ""},
      {"finish {}", ""},
  };
  const std::vector<std::string> bad_files = {"missing.yaml", "adir",      "/dev/null",
                                              "latin1.txt",   "empty.txt", "garbage.json"};
  for (const auto& [pattern, unused] : file_options)
    for (const std::string& f : bad_files) {
      std::string args = pattern;
      args.replace(args.find("{}"), 2, f);
      cases.push_back({args, f == "/dev/null" ? "null" : f, ""});
    }

  // 3. Pipeline keys through --set on validate: wrong type, out of range, unknown.
  const std::vector<std::pair<std::string, std::vector<std::string>>> keys = {
      {"seed", {"abc", "1.5", "[1,2]", "'{a: 1}'"}},
      {"version", {"2", "abc", "-1"}},
      {"resolution", {"-1", "0", "nan", "inf", "abc", "[1]"}},
      {"resampling", {"sideways", "1", "[a]"}},
      {"output.preview", {"maybe", "2", "[1]"}},
      {"output.exr", {"maybe", "[1]"}},
      {"output.formats", {"[bmp]", "7", "'{a: 1}'"}},
      {"output.tiles.size", {"-1", "0", "abc", "nan", "1e400"}},
      {"output.compress", {"zip7", "[1]"}},
      {"output.crs", {"EPSG:0", "nonsense", "[1]"}},
      {"avoidance.max_distance", {"-1", "nan", "abc"}},
      {"repair.merge_distance", {"-1", "nan", "abc"}},
      {"repair.spike_angle", {"-1", "nan", "abc", "400"}},
      {"repair.min_loop", {"-1", "nan", "abc"}},
      {"synthesis_resolution", {"-1", "0", "nan", "abc"}},
      {"features.roads.width", {"-1", "0", "nan", "inf", "abc", "[6]"}},
      {"features.roads.kind", {"spaceship", "[road]", "1"}},
      {"features.roads.source", {"missing.gpkg", "adir", "/dev/null", "latin1.txt", "[1]"}},
      {"heightfield", {"missing.tif", "adir", "/dev/null", "latin1.txt", "[1]"}},
      {"backend", {"gpu9", "[1]"}},
      {"precedence", {"7", "[nothing]"}},
      {"synthesis_order", {"sideways", "[1]"}},
  };
  for (const std::string v : {"-1", "abc", "nan", "1e400"})
    cases.push_back(
        {"validate pipeline.yaml --set output.tiles.size=24 --set output.tiles.overlap=" + v,
         "output.tiles.overlap", ""});
  // A layer, filter or attribute the source lacks: named with the class and the source.
  for (const std::string set :
       {"features.roads.layer=nolayer", "features.roads.layer=[1]",
        "'features.roads.where=width >< 3'", "features.roads.width_attribute=nofield"})
    cases.push_back({"validate pipeline.yaml --set " + set, "features.roads", ""});
  for (const auto& [key, values] : keys)
    for (const std::string& v : values)
      cases.push_back({"validate pipeline.yaml --set " + key + "=" + v, key, ""});
  for (const char* unknown :
       {"sede", "output.bogus", "features.roads.widht", "repair.bogus", "output.tiles.bogus",
        "generate.bogus", "avoidance.bogus", "features.roads.synthesis.bogus"})
    cases.push_back({"validate pipeline.yaml --set " + std::string(unknown) + "=1", unknown, ""});
  cases.push_back({"validate pipeline.yaml --set seed", "--set seed", ""});
  cases.push_back({"validate pipeline.yaml --set =1", "--set =1", ""});

  // 4. Run and plan files corrupted: each case works on its own copy (c).
  const std::string plan = "@c/.terraweave/plan";
  const std::vector<std::pair<std::string, std::string>> plan_files = {
      {"job.json", "render-tile @c --tile 0"},   {"plan.json", "render-tile @c --tile 0"},
      {"tasks.json", "render-tile @c --tile 0"}, {"job.json", "finish @c"},
      {"job.json", "complete-plan @c"},
  };
  for (const auto& [file, command] : plan_files) {
    for (const std::string bytes : {"{\\\"format\\\": ", "[1,2]", "\\377\\376", ""}) {
      cases.push_back(
          {command, file, "cp -r plan1 @c && printf \"" + bytes + "\" > " + plan + "/" + file});
    }
  }
  const std::vector<std::pair<std::string, std::string>> run_files = {
      {"report.json", "view @c --no-verify --out @o/v.html"},
      {"report.json", "export @c --to godot --no-verify --out @o"},
      {"report.json", "diff @c run1 --no-verify"},
      {"report.json", "diff run1 @c --no-verify"},
      {"features.geojson", "view @c --no-verify --out @o/v.html"},
      {"features.geojson", "export @c --to godot --no-verify --out @o"},
  };
  for (const auto& [file, command] : run_files)
    for (const std::string bytes :
         {"{\\\"format\\\": ", "\\377\\376", "", "{\\\"features\\\": 3}"}) {
      if (file == "report.json" && bytes == "{\\\"features\\\": 3}") continue;
      cases.push_back({command, file, "cp -r run1 @c && printf \"" + bytes + "\" > @c/" + file});
    }
  // A tiled run's mosaic with a tile gone.
  cases.push_back({"view @c --no-verify --out @o/v.html", "tile",
                   "cp -r tiled1 @c && rm @c/$(sed -n 's:.*<SourceFilename[^>]*>"
                   "\\(.*\\)</SourceFilename>.*:\\1:p' @c/height.vrt | head -1)"});
  return cases;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at))
    text.replace(at, from.size(), to), at += to.size();
  return text;
}

TEST_F(BadInputCorpus, EveryBadInputEndsInOneCleanErrorNamingIt) {
  const fs::path& d = dir_->path();
  const TempDir logs;
  std::vector<Case> cases = corpus();
  EXPECT_GE(cases.size(), 400u);
  // Case i writes to o_i and works on its copy c_i, so what it leaves behind is its own.
  std::string prepare = "set -e\ncd " + quoted(d.string()) + "\n";
  std::string batch = "cd " + quoted(d.string()) + "\n";
  for (std::size_t i = 0; i < cases.size(); ++i) {
    Case& c = cases[i];
    const std::string n = std::to_string(i);
    c.args = replaced(replaced(c.args, "@o", "o_" + n), "@c", "c_" + n);
    c.prepare = replaced(c.prepare, "@c", "c_" + n);
    if (!c.prepare.empty()) prepare += c.prepare + "\n";
    // The shell splits the arguments (quotes as typed); each field ends with a tab.
    batch += "printf '%s\\t' " + quoted(d.string()) + " " +
             quoted((logs.path() / (n + ".out")).string()) + " " +
             quoted((logs.path() / (n + ".err")).string()) + " -q " + c.args + "; echo\n";
  }
  std::ofstream(logs.path() / "prepare.sh") << prepare;
  std::ofstream(logs.path() / "batch.sh") << batch;
  ASSERT_EQ(std::system(("sh " + quoted((logs.path() / "prepare.sh").string())).c_str()), 0);
  const fs::path list = logs.path() / "batch.txt";
  ASSERT_EQ(std::system(("sh " + quoted((logs.path() / "batch.sh").string()) + " > " +
                         quoted(list.string()))
                            .c_str()),
            0);
  const auto before = snapshot(d);
  const auto started = std::chrono::steady_clock::now();
  // One process loads the program; every case runs in a child forked from it (src/cli/main.cpp,
  // TERRAWEAVE_FORK_BATCH): the same program, its own exit code and signals.
  ASSERT_EQ(std::system(("TERRAWEAVE_FORK_BATCH=" + quoted(list.string()) + " " +
                         quoted(terraweave_binary().string()))
                            .c_str()),
            0);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const auto after = snapshot(d);
  std::vector<int> statuses;
  std::istringstream status_text(read_file(fs::path(list.string() + ".status")));
  for (int st; status_text >> st;) statuses.push_back(st);
  ASSERT_EQ(statuses.size(), cases.size());

  // What changed, by case (o_i, c_i); anything else belongs to no case and is an error too.
  std::map<std::size_t, std::vector<std::string>> written;
  std::vector<std::string> stray;
  std::set<std::string> names;
  for (const auto& [name, stamp] : before) names.insert(name);
  for (const auto& [name, stamp] : after) names.insert(name);
  for (const std::string& name : names) {
    const auto b = before.find(name), a = after.find(name);
    if (b != before.end() && a != after.end() && b->second == a->second) continue;
    const std::string top = name.substr(0, name.find('/'));
    if ((top.starts_with("o_") || top.starts_with("c_")) &&
        top.find_first_not_of("0123456789", 2) == std::string::npos)
      written[std::stoul(top.substr(2))].push_back(name);
    else
      stray.push_back(name);
  }
  EXPECT_TRUE(stray.empty()) << "written by some case: " << ::testing::PrintToString(stray);

  std::map<std::string, int> outcomes;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    const int status = statuses[i];
    const std::string err = read_file(logs.path() / (std::to_string(i) + ".err"));
    const std::vector<std::string> lines = lines_of(err);
    int error_lines = 0;
    for (const std::string& l : lines)
      if (l.starts_with("terraweave: error:") || l.starts_with("terraweave: usage error:"))
        ++error_lines;
    const int code = status >= 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::string outcome;
    if (status < 0 || !WIFEXITED(status) || code >= 124)
      outcome = "crash or signal";
    else if (code == 0)
      outcome = "wrong exit (0)";
    else if (code != 1 && code != 2)
      outcome = "wrong exit (other)";
    else if (lines.empty() || error_lines != 1 ||
             !(lines.back().starts_with("terraweave: error:") ||
               lines.back().starts_with("terraweave: usage error:")))
      outcome = "not one error line";
    else if (lines.back().find(c.expect) == std::string::npos)
      outcome = "missing name";
    else if (lines.back().find("[json.exception") != std::string::npos)
      outcome = "raw library text";
    else if (written.count(i))
      outcome = "wrote files";
    else
      outcome = "clean error";
    ++outcomes[outcome];
    EXPECT_EQ(outcome, "clean error")
        << "terraweave -q " << c.args << "\n  (prepared by: " << c.prepare << ")\n  status "
        << status << ", exit " << code << ", expected to name: " << c.expect << "\n  stderr:\n"
        << err << (written.count(i) ? "  wrote: " + ::testing::PrintToString(written[i]) : "");
  }
  std::printf("bad-input corpus: %zu cases in %.1f s\n", cases.size(), seconds);
  for (const auto& [outcome, count] : outcomes) std::printf("  %-20s %d\n", outcome.c_str(), count);
}

}  // namespace
}  // namespace tw::test
