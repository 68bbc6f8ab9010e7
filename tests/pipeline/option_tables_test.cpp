// Issue #24 item 2: every option of every command changes what the command writes or prints, or
// is documented not to (docs/cli.md, "Options that change no bytes") and then changes no byte.
// One table per command (one test each, so ctest runs them in parallel): each row runs the
// command with the option at A and at B over the same tiny inputs; the table must name exactly
// the options `--help` lists, so an option added without a row fails, and an option ignored
// again fails its row. `grow` has its table in grow_command_test.cpp (GrowOptions).
#include <fmt/format.h>
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fstream>
#include <map>
#include <memory>

#include "option_table.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* kCrs = R"("crs": {"type": "name", "properties": {"name": "EPSG:32631"}})";

std::string geojson(const std::string& features) {
  return std::string(R"({"type": "FeatureCollection", )") + kCrs + R"(, "features": [)" + features +
         "]}";
}
std::string polygon(const std::string& name, double x0, double y0, double x1, double y1) {
  return fmt::format(
      R"({{"type": "Feature", "properties": {{"name": "{}"}}, "geometry": {{"type": "Polygon",
      "coordinates": [[[{},{}],[{},{}],[{},{}],[{},{}],[{},{}]]]}}}})",
      name, x0, y0, x1, y0, x1, y1, x0, y1, x0, y0);
}
std::string line(const std::string& coordinates, const std::string& properties = "{}") {
  return R"({"type": "Feature", "properties": )" + properties +
         R"(, "geometry": {"type": "LineString", "coordinates": )" + coordinates + "}}";
}

// The pipeline of the run-like tables: the 64 x 64 test DEM (with a nodata corner) and two
// roads, tiled; ${res} from the variables file.
const char* const kPipeline = R"(version: 1
seed: 3
heightfield: dem.tif
resolution: ${res}
output: { dir: out, preview: false, tiles: { size: 32 } }
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 6 }
)";

class OptionTables : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(d);
    DemSpec spec;
    spec.nodata = -9999.0;
    write_dem(d / "dem.tif", spec);
    {  // a nodata corner, for export --nodata-height
      GDALAllRegister();
      std::unique_ptr<GDALDataset> dem(
          GDALDataset::Open((d / "dem.tif").c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE));
      ASSERT_TRUE(dem);
      std::vector<float> hole(16, -9999.0f);
      ASSERT_EQ(dem->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 4, 4, hole.data(), 4, 4,
                                                GDT_Float32, 0, 0),
                CE_None);
    }
    write_layer(d / "map.gpkg", "roads",
                {{"LINESTRING (500020 5000300, 500600 5000250)", 6.0},
                 {"LINESTRING (500300 5000020, 500320 5000600)", 8.0}});
    write_layer(d / "map.gpkg", "paths",
                {{"LINESTRING (500100 5000500, 500118 5000500)", 4.0},
                 {"LINESTRING (500400 5000100, 500418 5000104)", 4.0}});
    // A repeated vertex: repaired with a warning (for --strict).
    write_layer(d / "map.gpkg", "dup",
                {{"LINESTRING (500020 5000300, 500020 5000300, 500600 5000250)", 6.0}});
    std::ofstream(d / "p.yaml") << kPipeline;
    std::string p2 = kPipeline;
    p2.replace(p2.find("width: 6"), 8, "width: 9");
    std::ofstream(d / "p2.yaml") << p2;
    std::ofstream(d / "v1.yaml") << "res: 10\n";
    std::ofstream(d / "v2.yaml") << "res: 20\n";
    std::string warn = kPipeline;
    warn.replace(warn.find("layer: roads"), 12, "layer: dup");
    std::ofstream(d / "warn.yaml") << warn;
    // Two 18 m paths with a pattern synthesized along them (for --backend, --threads, --cache).
    std::ofstream(d / "ps.yaml") << fmt::format(R"(version: 1
seed: 3
heightfield: dem.tif
output: {{ dir: out, preview: false, tiles: {{ size: 32 }} }}
features:
  paths:
    source: map.gpkg
    layer: paths
    kind: road
    width: 4
    synthesis: {{ exemplar: {}, scale: 4, width: 4, delta: 3 }}
)",
                                                chain);
  }

  // Runs of p.yaml in the data folder for the tables that read a run: r1, r2 (other road
  // widths) and r1c, r1 with features.geojson edited after the run.
  void make_runs(Batch& batch) {
    const Invocation r1{words("-q run @d/p.yaml --vars @d/v1.yaml --out r")};
    const Invocation r2{
        words("-q run @d/p.yaml --vars @d/v1.yaml --set features.roads.width=9 --out r")};
    batch.run({r1, r2});
    ASSERT_EQ(batch[r1].exit_code, 0) << batch[r1].err;
    ASSERT_EQ(batch[r2].exit_code, 0) << batch[r2].err;
    fs::copy(batch.folder_of(r1) / "r", d / "r1", fs::copy_options::recursive);
    fs::copy(batch.folder_of(r2) / "r", d / "r2", fs::copy_options::recursive);
    fs::copy(d / "r1", d / "r1c", fs::copy_options::recursive);
    std::string features = read_file(d / "r1c/features.geojson");
    const std::size_t at = features.find("500020");
    ASSERT_NE(at, std::string::npos);
    features.replace(at, 6, "500021");
    std::ofstream(d / "r1c/features.geojson", std::ios::binary | std::ios::trunc) << features;
  }

  // A row whose A and B are `base` followed by `a` and by `b`.
  static OptionRow row(const std::string& option, const std::string& base, const std::string& a,
                       const std::string& b, Expect expect = Expect::changes,
                       const std::string& doc = "", int a_exit = 0, int b_exit = 0) {
    return {option, {words(base + " " + a)}, {words(base + " " + b)}, expect, doc, a_exit, b_exit};
  }

  TempDir dir;
  const fs::path d = dir / "d";
  Batch batch{d, dir / "w"};
  const std::string samples = (source_dir() / "samples").string();
  const std::string chain = samples + "/exemplars/chain_199x82.png";
};

// Every command `terraweave --help` lists (and their subcommands) has a table here or in
// grow_command_test.cpp.
TEST_F(OptionTables, EveryCommandHasATable) {
  const std::set<std::string> tabled = {"run",
                                        "validate",
                                        "schema",
                                        "diff",
                                        "view",
                                        "plan",
                                        "synth-feature",
                                        "complete-plan",
                                        "render-tile",
                                        "finish",
                                        "synth",
                                        "area",
                                        "grow",
                                        "network clone",
                                        "network complete",
                                        "network synthesize",
                                        "exemplar inspect",
                                        "export"};
  EXPECT_EQ(leaf_commands(), tabled);
  EXPECT_EQ(help_options("schema"), std::set<std::string>{});  // schema's table: no option
}

TEST_F(OptionTables, Global) {
  const std::string run = "run @d/p.yaml --vars @d/v1.yaml --out out";
  const std::string ps = "run @d/ps.yaml --out out";
  const std::string url =
      "validate @d/p.yaml --vars @d/v1.yaml --set "
      "heightfield=/vsicurl/http://127.0.0.1:9/dem.tif";
  std::vector<OptionRow> rows = {
      {"--version", {words("-q " + run)}, {words("--version")}},
      {"--verbose",
       {words(run)},
       {words("-v " + run)},
       Expect::log_only,
       "docs/cli.md: `-v` logs debug lines"},
      {"--quiet",
       {words(run)},
       {words("-q " + run)},
       Expect::log_only,
       "docs/cli.md: `-q` only warnings. Logs go to stderr."},
      {"--threads",
       {words("-q --threads 1 " + ps)},
       {words("-q --threads 2 " + ps)},
       Expect::same_bytes,
       "docs/cli.md: outputs are identical for any count"},
      {"--strict",
       {words("-q run @d/warn.yaml --vars @d/v1.yaml --out out")},
       {words("-q --strict run @d/warn.yaml --vars @d/v1.yaml --out out")},
       Expect::changes,
       "",
       0,
       1},
      {"--allow-network",
       {words("-q " + url)},
       {words("-q --allow-network " + url)},
       Expect::changes,
       "",
       1,
       1},
  };
  check_option_rows("terraweave", help_options(""), rows, batch);
}

TEST_F(OptionTables, Run) {
  const std::string base = "-q run";
  const std::string p = "@d/p.yaml --vars @d/v1.yaml";
  std::vector<OptionRow> rows = {
      row("PIPELINE", base, p + " --out out", "@d/p2.yaml --vars @d/v1.yaml --out out"),
      row("--set", base, p + " --out out", p + " --out out --set features.roads.width=9"),
      row("--vars", base, p + " --out out", "@d/p.yaml --vars @d/v2.yaml --out out"),
      row("--seed", base, "@d/ps.yaml --out out", "@d/ps.yaml --out out --seed 4"),
      {"--out",
       {words(base + " " + p + " --out out"), {}, {}, "out"},
       {words(base + " " + p + " --out sub/elsewhere"), {}, {}, "sub/elsewhere"},
       Expect::same_bytes,
       "docs/cli.md: Where the files go (`--out`, `-o`, `--cache`) does not change what they hold"},
      row("--backend", base, "@d/ps.yaml --out out --backend cpu",
          "@d/ps.yaml --out out --backend opencl", Expect::same_bytes,
          "docs/cli.md: outputs are the same bytes on either"),
      // A warm cache: the second run reuses the first one's syntheses and tiles.
      {"--cache",
       {words(base + " @d/ps.yaml --out out"), {}, {}, "out"},
       {words(base + " @d/ps.yaml --out out --cache c"),
        {words(base + " @d/ps.yaml --out first --cache c")},
        {},
        "out"},
       Expect::same_bytes,
       "docs/cli.md: Where the files go (`--out`, `-o`, `--cache`) does not change what they hold"},
  };
  check_option_rows("run", help_options("run"), rows, batch);
}

TEST_F(OptionTables, Validate) {
  const std::string base = "-q validate";
  const std::string p = "@d/p.yaml --vars @d/v1.yaml";
  std::vector<OptionRow> rows = {
      row("PIPELINE", base, p, "@d/p2.yaml --vars @d/v1.yaml"),
      row("--set", base, p, p + " --set features.roads.layer=dup"),
      row("--vars", base, p, "@d/p.yaml --vars @d/v2.yaml"),
      row("--seed", base, p, p + " --seed 4", Expect::same_bytes,
          "docs/cli.md: `validate` prints the same line for any `--seed`"),
  };
  check_option_rows("validate", help_options("validate"), rows, batch);
}

TEST_F(OptionTables, Plan) {
  const std::string base = "-q plan";
  const std::string p = "@d/p.yaml --vars @d/v1.yaml --out out";
  const std::string ps = "@d/ps.yaml --out out";
  // Plan A and plan B, render every tile and finish: the run folders compared.
  auto finished = [&](const std::string& option, const std::string& a, const std::string& b,
                      const std::string& b_out,
                      const std::string& doc =
                          "docs/cli.md: Where the files go (`--out`, `-o`, "
                          "`--cache`) does not change what they hold") {
    auto steps = [&](const std::string& plan, const std::string& out) {
      std::vector<std::vector<std::string>> s = {words(base + " " + plan)};
      for (const char* t : {"0", "1", "2", "3"})
        s.push_back(words("-q render-tile " + out + " --tile " + t));
      return s;
    };
    return OptionRow{option,
                     {words("-q finish out"), steps(a, "out"), {}, "out", ".terraweave/"},
                     {words("-q finish " + b_out), steps(b, b_out), {}, b_out, ".terraweave/"},
                     Expect::same_bytes,
                     doc};
  };
  std::vector<OptionRow> rows = {
      row("PIPELINE", base, p, "@d/p2.yaml --vars @d/v1.yaml --out out"),
      row("--set", base, p, p + " --set features.roads.width=9"),
      row("--vars", base, p, "@d/p.yaml --vars @d/v2.yaml --out out"),
      row("--seed", base, ps, ps + " --seed 4"),
      // A plan records where its run goes, its backend and its cache (job.json): what a plan
      // promises is the run it finishes as, the same bytes.
      finished("--out", p, "@d/p.yaml --vars @d/v1.yaml --out sub/elsewhere", "sub/elsewhere"),
      finished("--backend", ps + " --backend cpu", ps + " --backend opencl", "out",
               "docs/cli.md: outputs are the same bytes on either"),
      finished("--cache", ps, ps + " --cache c", "out"),
      row("--synthesis", base, ps + " --synthesis inline", ps + " --synthesis tasks"),
  };
  check_option_rows("plan", help_options("plan"), rows, batch);
}

// `plan --seed` and `plan --vars` reach the tasks: they read the pipeline again (job.json) and
// once did so without them (render-tile failed on ${res}; synth-feature drew with the file's
// seed), so a distributed run of them is the plain run's bytes.
TEST_F(OptionTables, PlanSeedAndVariablesReachTheTasks) {
  std::ofstream(d / "psv.yaml") << read_file(d / "ps.yaml") + "resolution: ${res}\n";
  const std::string pipeline = "@d/psv.yaml --vars @d/v1.yaml --seed 4";
  std::vector<std::vector<std::string>> steps = {
      words("-q plan " + pipeline + " --out out --synthesis tasks"),
      words("-q synth-feature out --feature 0"), words("-q synth-feature out --feature 1"),
      words("-q complete-plan out")};
  for (const char* t : {"0", "1", "2", "3"})
    steps.push_back(words(std::string("-q render-tile out --tile ") + t));
  const Invocation distributed{words("-q finish out"), steps, {}, "out", ".terraweave/"};
  const Invocation plain{words("-q run " + pipeline + " --out out"), {}, {}, "out", ".terraweave/"};
  const Invocation other_seed{
      words("-q run @d/psv.yaml --vars @d/v1.yaml --out out"), {}, {}, "out", ".terraweave/"};
  batch.run({distributed, plain, other_seed});
  ASSERT_EQ(batch[distributed].exit_code, 0) << batch[distributed].err;
  ASSERT_EQ(batch[plain].exit_code, 0) << batch[plain].err;
  EXPECT_FALSE(batch[plain].files.empty());
  EXPECT_EQ(batch[distributed].files, batch[plain].files);
  EXPECT_NE(batch[other_seed].files, batch[plain].files);  // the seed matters here
}

// The distributed steps: each measured step after the steps before it, over two plans (out,
// out2: other seeds, or other road widths).
TEST_F(OptionTables, DistributedSteps) {
  const auto steps = [](const std::string& out, const std::string& seed, bool tasks) {
    // Syntheses of the paths' patterns with two seeds; tiles of the world without patterns
    // (cheaper) with two road widths.
    const std::string pipeline = seed == "3" ? "@d/p.yaml" : "@d/p2.yaml";
    std::vector<std::vector<std::string>> s = {
        words(tasks ? "-q plan @d/ps.yaml --synthesis tasks --out " + out + " --seed " + seed
                    : "-q plan " + pipeline + " --vars @d/v1.yaml --out " + out)};
    return s;
  };
  auto both = [&](bool tasks) {
    auto s = steps("out", "3", tasks);
    for (auto& step : steps("out2", "4", tasks)) s.push_back(step);
    return s;
  };
  auto synthesized = [&]() {
    auto s = both(true);
    for (const char* out : {"out", "out2"})
      for (const char* f : {"0", "1"})
        s.push_back(words(std::string("-q synth-feature ") + out + " --feature " + f));
    return s;
  };
  auto rendered = [&]() {
    auto s = both(false);
    for (const char* out : {"out", "out2"})
      for (const char* t : {"0", "1", "2", "3"})
        s.push_back(words(std::string("-q render-tile ") + out + " --tile " + t));
    return s;
  };
  const auto tasks = both(true), plans = both(false), done = synthesized(), tiles = rendered();
  const std::vector<OptionRow> synth_feature = {
      {"PLAN",
       {words("-q synth-feature out --feature 0"), tasks},
       {words("-q synth-feature out2 --feature 0"), tasks}},
      {"--feature",
       {words("-q synth-feature out --feature 0"), tasks},
       {words("-q synth-feature out --feature 1"), tasks}},
  };
  check_option_rows("synth-feature", help_options("synth-feature"), synth_feature, batch);
  const std::vector<OptionRow> complete = {
      {"PLAN", {words("-q complete-plan out"), done}, {words("-q complete-plan out2"), done}},
  };
  check_option_rows("complete-plan", help_options("complete-plan"), complete, batch);
  const std::vector<OptionRow> render = {
      {"PLAN",
       {words("-q render-tile out --tile 0"), plans},
       {words("-q render-tile out2 --tile 0"), plans}},
      {"--tile",
       {words("-q render-tile out --tile 0"), plans},
       {words("-q render-tile out --tile 1"), plans}},
  };
  check_option_rows("render-tile", help_options("render-tile"), render, batch);
  const std::vector<OptionRow> finish = {
      {"PLAN", {words("-q finish out"), tiles}, {words("-q finish out2"), tiles}},
  };
  check_option_rows("finish", help_options("finish"), finish, batch);
}

TEST_F(OptionTables, RunReaders) {
  make_runs(batch);
  const std::vector<OptionRow> diff = {
      row("RUN_A", "-q diff", "@d/r1 @d/r1", "@d/r2 @d/r1", Expect::changes, "", 0, 1),
      row("RUN_B", "-q diff", "@d/r1 @d/r1", "@d/r1 @d/r2", Expect::changes, "", 0, 1),
      row("--no-verify", "-q diff", "@d/r1 @d/r1c", "@d/r1 @d/r1c --no-verify", Expect::changes, "",
          2, 1),
  };
  check_option_rows("diff", help_options("diff"), diff, batch);

  // A port taken by this process: `view --serve` starts python3's server, which cannot bind it
  // and exits 1 after the page is written and "serving ..." printed.
  const int server = socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(server, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(bind(server, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  ASSERT_EQ(listen(server, 1), 0);
  socklen_t length = sizeof address;
  ASSERT_EQ(getsockname(server, reinterpret_cast<sockaddr*>(&address), &length), 0);
  const std::string port = std::to_string(ntohs(address.sin_port));
  std::vector<OptionRow> view = {
      row("RUN_DIR", "-q view", "@d/r1 --out v.html", "@d/r2 --out v.html"),
      {"--out",
       {words("-q view @d/r1 --out v.html")},
       {words("-q view @d/r1 --out sub/v.html"), {}, {}, "sub"},
       Expect::same_bytes,
       "docs/cli.md: Where the files go (`--out`, `-o`, `--cache`) does not change what they hold"},
      row("--no-verify", "-q view", "@d/r1c --out v.html", "@d/r1c --out v.html --no-verify",
          Expect::changes, "", 1, 0),
      row("--serve", "-q view", "@d/r1 --out v.html", "@d/r1 --out v.html --serve " + port,
          Expect::changes, "", 0, 1),
  };
  // The drawing page's options act in the server's answers: tested against the running server.
  for (const char* option : {"--exemplar", "--where", "--scale", "--seed", "--save"})
    view.push_back({option,
                    {},
                    {},
                    Expect::tested_by,
                    "tests/pipeline/network_page_test.cpp: "
                    "NetworkPage.EveryDrawingOptionChangesWhatTheServerAnswersOrWrites"});
  check_option_rows("view", help_options("view"), view, batch);
  close(server);

  const std::string e = "-q export";
  const std::vector<OptionRow> exports = {
      row("RUN_DIR", e, "@d/r1 --to unity --out e", "@d/r2 --to unity --out e"),
      row("--to", e, "@d/r1 --to unity --out e", "@d/r1 --to godot --out e"),
      {"--out",
       {words(e + " @d/r1 --to unity --out e"), {}, {}, "e"},
       {words(e + " @d/r1 --to unity --out sub/e"), {}, {}, "sub/e"},
       Expect::same_bytes,
       "docs/cli.md: Where the files go (`--out`, `-o`, `--cache`) does not change what they hold"},
      // One heightmap: with tiles the tile size decides (and --size is a warning).
      row("--size", e, "@d/r1 --to unity --out e --tile-size 0 --size 65",
          "@d/r1 --to unity --out e --tile-size 0 --size 129"),
      row("--input-height", e, "@d/r1 --to unity --out e --tile-size 0",
          "@d/r1 --to unity --out e --tile-size 0 --input-height @d/dem.tif"),
      row("--no-verify", e, "@d/r1c --to unity --out e", "@d/r1c --to unity --out e --no-verify",
          Expect::changes, "", 1, 0),
      row("--tile-size", e, "@d/r1 --to unity --out e --tile-size 0",
          "@d/r1 --to unity --out e --tile-size 33"),
      row("--nodata-height", e, "@d/r1 --to unity --out e",
          "@d/r1 --to unity --out e --nodata-height -50"),
      row("--godot-height", e, "@d/r1 --to godot --out e --godot-height exr",
          "@d/r1 --to godot --out e --godot-height r16"),
  };
  check_option_rows("export", help_options("export"), exports, batch);
}

TEST_F(OptionTables, Synth) {
  using Args = std::map<std::string, std::string>;  // option -> value ("" for a flag)
  const Args base = {{"--exemplar", chain},  {"--scale", "4"},     {"--backend", "cpu"},
                     {"--curve", "s-curve"}, {"--length", "24"},   {"--width", "4"},
                     {"--delta", "3"},       {"--output", "s.png"}};
  const auto synth = [&](const Args& changed) {
    Args args = base;
    for (const auto& [option, value] : changed) args[option] = value;
    std::vector<std::string> line = {"-q", "synth"};
    for (const auto& [option, value] : args) {
      line.push_back(option);
      if (!value.empty()) line.push_back(value);
    }
    return Invocation{line};
  };
  const auto r = [&](const std::string& option, const Args& a, const Args& b,
                     Expect expect = Expect::changes, const std::string& doc = "") {
    return OptionRow{option, synth(a), synth(b), expect, doc};
  };
  Invocation moved = synth({{"--output", "sub/s.png"}});
  moved.folder = "sub";
  const std::vector<OptionRow> rows = {
      r("--exemplar", {}, {{"--exemplar", samples + "/exemplars/hedge_192x48.png"}}),
      r("--curve", {}, {{"--curve", "arc"}}),
      r("--length", {}, {{"--length", "30"}}),
      r("--width", {}, {{"--width", "5"}}),
      r("--delta", {}, {{"--delta", "4"}}),
      r("--scale", {}, {{"--scale", "5"}}),
      r("--backend", {}, {{"--backend", "opencl"}}, Expect::same_bytes,
        "docs/cli.md: `synth` writes the same bytes with either backend"),
      r("--seed", {}, {{"--seed", "3"}}),
      {"--output", synth({}), moved, Expect::same_bytes,
       "docs/cli.md: Where the files go (`--out`, `-o`, `--cache`) does not change what they hold"},
      r("--placements", {}, {{"--placements", "p.json"}}),
      // The optimum of the default floor is valid up to 0.6; at 0.7 it is not.
      r("--min-coverage", {}, {{"--min-coverage", "0.7"}}),
      r("--objective", {}, {{"--objective", "paper"}}),
      r("--coverage-weight", {}, {{"--coverage-weight", "20"}}),
      r("--no-stitch", {}, {{"--no-stitch", ""}}),
      r("--feather", {}, {{"--feather", "1"}}),
      r("--alpha", {}, {{"--alpha", "continuous"}}),
  };
  check_option_rows("synth", help_options("synth"), rows, batch);
}

TEST_F(OptionTables, ExemplarInspect) {
  const std::string ridge = samples + "/exemplars/ridge_band_200x64.png";
  const std::string url = "/vsicurl/http://127.0.0.1:9/e.png";
  const std::vector<OptionRow> rows = {
      row("image", "-q exemplar inspect", ridge, chain),
      row("--preview", "-q exemplar inspect " + ridge, "", "--preview p.png"),
      row("--json", "-q exemplar inspect " + ridge, "", "--json"),
      row("--allow-network", "-q exemplar inspect " + url, "", "--allow-network", Expect::changes,
          "", 1, 1),
  };
  check_option_rows("exemplar inspect", help_options("exemplar inspect"), rows, batch);
}

TEST_F(OptionTables, Area) {
  std::ofstream(d / "fields.geojson")
      << geojson(polygon("a", 500000, 5000000, 500200, 5000160) + "," +
                 polygon("b", 500300, 5000000, 500460, 5000200));
  std::ofstream(d / "other.geojson") << geojson(polygon("c", 500000, 5000000, 500180, 5000200));
  // A track without a width attribute across both fields.
  std::ofstream(d / "track.geojson") << geojson(line("[[500100, 4999950], [500400, 5000250]]"));
  const std::string sketches = samples + "/sketches/";
  const std::string base = "-q area " + sketches + "orchard.geojson --out out";
  const std::string p = " --polygons @d/fields.geojson --scale 40";
  const std::vector<OptionRow> rows = {
      row("sketch", "-q area --out out" + p, sketches + "orchard.geojson",
          sketches + "vineyard.geojson"),
      row("--polygons", base + " --scale 40", "--polygons @d/fields.geojson",
          "--polygons @d/other.geojson"),
      row("--where", base, p + " --where name~=~'a'", p + " --where name~=~'b'"),
      row("--shapes-from", base, p, p + " --shapes-from " + sketches + "boulders.geojson"),
      row("--scale", base + " --polygons @d/fields.geojson", "--scale 40", "--scale 30"),
      row("--bearing", base, p, p + " --bearing 30"),
      row("--seed", base, p, p + " --seed 2"),
      row("--jitter", base, p + " --jitter 0", p + " --jitter 1"),
      row("--avoid", base, p, p + " --avoid @d/map.gpkg:roads"),
      row("--avoid-width", base, p + " --avoid @d/track.geojson --avoid-width 4",
          p + " --avoid @d/track.geojson --avoid-width 40"),
      // The lattice where shapes meet what they avoid.
      row("--resolution", base, p + " --avoid @d/map.gpkg:roads --resolution 1",
          p + " --avoid @d/map.gpkg:roads --resolution 4"),
      row("--analysis-png", base, p, p + " --analysis-png a.png"),
      {"--out",
       {words(base + p), {}, {}, "out"},
       {words("-q area " + sketches + "orchard.geojson --out sub/out" + p), {}, {}, "sub/out"},
       Expect::same_bytes,
       "docs/cli.md: Where the files go (`--out`, `-o`, `--cache`) does not change what they hold"},
  };
  check_option_rows("area", help_options("area"), rows, batch);
}

// A small grid of fields (UTM 31N metres, as network_command_test.cpp's), its lines attributed
// alternately kind a and b; an SVG of a few lines; a region polygon.
void write_network_inputs(const fs::path& d) {
  std::string features;
  int k = 0;
  auto add = [&](int x0, int y0, int x1, int y1) {
    features += std::string(features.empty() ? "" : ",") +
                line(fmt::format("[[{},{}],[{},{}]]", x0, y0, x1, y1),
                     fmt::format(R"({{"kind": "{}"}})", k++ % 2 ? "a" : "b"));
  };
  for (int i = 0; i <= 6; ++i) add(500000 + i * 100, 4000000, 500000 + i * 100, 4000480);
  for (int j = 0; j <= 6; ++j)
    for (int i = 0; i < 6; ++i) {
      if ((i + j) % 3 == 1 && j > 0 && j < 6) continue;
      const int y = 4000000 + j * 80 + ((i * 7 + j) % 3) * 6 * (j > 0 && j < 6);
      add(500000 + i * 100, y, 500000 + (i + 1) * 100, y);
    }
  std::ofstream(d / "fields.geojson") << geojson(features);
  // The same grid with every horizontal line 4 m short of the vertical line it ends on.
  features.clear();
  for (int i = 0; i <= 6; ++i) add(500000 + i * 100, 4000000, 500000 + i * 100, 4000480);
  for (int j = 1; j < 6; ++j)
    for (int i = 0; i < 6; ++i)
      add(500000 + i * 100, 4000000 + j * 80, 500096 + i * 100, 4000000 + j * 80);
  std::ofstream(d / "gappy.geojson") << geojson(features);
  std::ofstream(d / "west.geojson") << geojson(polygon("w", 500000, 4000000, 500350, 4000480));
  std::ofstream(d / "south.geojson") << geojson(polygon("s", 500000, 4000000, 500600, 4000250));
  std::ofstream(d / "drawn.geojson")
      << geojson(line("[[500050.125,4000300.5],[500450.25,4000302.75]]") + "," +
                 line("[[500450.25,4000302.75],[500449.5,4000650.0]]"));
  std::ofstream(d / "drawn2.geojson")
      << geojson(line("[[500050.125,4000200.5],[500450.25,4000202.75]]"));
  std::ofstream(d / "track.geojson") << geojson(line("[[500420, 3999950], [500480, 4000750]]"));
  // Across the region of complete, clear of the drawing (a drawn line across an avoided track
  // fails the check as "a growth bug").
  std::ofstream(d / "track_side.geojson")
      << geojson(line("[[500600, 3999950], [500640, 4000750]]"));
  std::ofstream(d / "track_east.geojson")
      << geojson(line("[[501000, 3999950], [501040, 4000750]]"));
  // Another exemplar: the grid's southern lines, moved a little.
  std::ofstream(d / "south_lines.geojson")
      << geojson(line("[[500000,4000000],[500000,4000250]]") + "," +
                 line("[[500100,4000000],[500110,4000250]]") + "," +
                 line("[[500000,4000100],[500110,4000100]]") + "," +
                 line("[[500000,4000200],[500110,4000210]]"));
  std::string svg = R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">)";
  for (int i = 0; i <= 4; ++i)
    svg += fmt::format(
        R"(<line x1="{0}" y1="0" x2="{0}" y2="100"/><line x1="0" y1="{0}" x2="100" y2="{1}"/>)",
        i * 25, i * 25 + (i % 2) * 3);
  std::ofstream(d / "grid.svg") << svg + "</svg>";
}

TEST_F(OptionTables, Network) {
  write_network_inputs(d);
  const std::string region = " --region 500000,4000000,500700,4000700";
  const std::string out_doc =
      "docs/cli.md: Where the files go (`--out`, `-o`, `--cache`) does not change what they hold";
  // The options every mode has, over `base` (the mode's command line, which holds --seed 4
  // --out out); --scale's row is given (an SVG's scale), --avoid's track is one crossing the
  // region grown.
  auto shared_rows = [&](const std::string& base, const OptionRow& scale, const std::string& track,
                         std::vector<OptionRow> rows) {
    auto replaced = [&](const std::string& from, const std::string& to) {
      std::string text = base;
      text.replace(text.find(from), from.size(), to);
      return Invocation{words(text)};
    };
    Invocation moved = replaced("--out out", "--out sub/out");
    moved.folder = "sub/out";
    const std::vector<OptionRow> more = {
        row("--where", base, "", "--where kind~=~'b'"),
        scale,
        row("--avoid", base, "", "--avoid " + track + " --avoid-width 10"),
        row("--avoid-width", base, "--avoid " + track + " --avoid-width 4",
            "--avoid " + track + " --avoid-width 60"),
        {"--seed", {words(base)}, replaced("--seed 4", "--seed 5")},
        row("--lead-bearing", base, "--lead-bearing 0", "--lead-bearing 45"),
        // The square region's long axis is north-south, as the exemplar's main bearing: against
        // a turned exemplar.
        row("--lead", base, "--lead-bearing 45", "--lead long_axis"),
        row("--clearance", base, "", "--clearance 30"),
        {"--out", {words(base), {}, {}, "out"}, moved, Expect::same_bytes, out_doc},
        // Pieces tried per stub, a knob of growth (`automatic` may keep the quilt).
        row("--candidates", base, "--method growth", "--method growth --candidates 2"),
    };
    rows.insert(rows.end(), more.begin(), more.end());
    return rows;
  };
  const std::string fields = " --exemplar @d/fields.geojson";
  // --snap over the exemplar whose horizontal lines stop 4 m short of the next vertical one.
  const std::string synth = "-q network synthesize" + region + " --seed 4 --out out";
  check_option_rows(
      "network synthesize", help_options("network synthesize"),
      shared_rows(
          synth + fields,
          row("--scale", synth + " --exemplar @d/grid.svg", "--scale 10", "--scale 14"),
          "@d/track.geojson",
          {row("--exemplar", synth, "--exemplar @d/fields.geojson",
               "--exemplar @d/south_lines.geojson"),
           row("--exemplar-region", synth + fields, "", "--exemplar-region @d/west.geojson"),
           row("--region", "-q network synthesize --seed 4 --out out" + fields, region,
               "--region 500000,4000000,500500,4000500"),
           row("--snap", synth + " --exemplar @d/gappy.geojson", "--snap 0.01", "--snap 6"),
           row("--method", synth + fields, "--method growth", "--method quilt"),
           row("--method", synth + fields, "--method growth", "--method layout")}),
      batch);
  const std::string complete = "-q network complete" + region + " --seed 4 --out out";
  const std::string drawn = " --partial @d/drawn.geojson";
  check_option_rows(
      "network complete", help_options("network complete"),
      shared_rows(
          complete + drawn + fields,
          row("--scale", complete + drawn + " --exemplar @d/grid.svg", "--scale 10", "--scale 14"),
          "@d/track_side.geojson",
          {row("--exemplar", complete + drawn, "--exemplar @d/fields.geojson",
               "--exemplar @d/south_lines.geojson"),
           row("--exemplar-region", complete + drawn + fields, "",
               "--exemplar-region @d/west.geojson"),
           row("--region", "-q network complete --seed 4 --out out" + drawn + fields, region,
               "--region 500000,4000000,500600,4000700"),
           row("--partial", complete + fields, drawn, "--partial @d/drawn2.geojson"),
           row("--snap", complete + drawn + " --exemplar @d/gappy.geojson", "--snap 0.01",
               "--snap 6"),
           // Completing a drawing is growth: the quilt and the layout are refused.
           row("--method", complete + drawn + fields, "--method growth", "--method quilt",
               Expect::changes, "", 0, 1),
           row("--method", complete + drawn + fields, "--method growth", "--method layout",
               Expect::changes, "", 0, 1)}),
      batch);
  const std::string target = " --target-region 500700,4000000,501300,4000480";
  const std::string source = " --source-region @d/west.geojson";
  const std::string map = " --map @d/fields.geojson";
  const std::string clone = "-q network clone --seed 4 --out out";
  check_option_rows(
      "network clone", help_options("network clone"),
      shared_rows(
          clone + target + source + map,
          // An SVG map of full-length lines crossing each other (noded in the target), its
          // regions boxes in its metres clear of its lines at both scales.
          row("--scale",
              clone + " --map @d/grid.svg --source-region 0,-1050,480,10" +
                  " --target-region 520,-1050,1100,10",
              "--scale 10", "--scale 14"),
          "@d/track_east.geojson",
          {row("--map", clone + target + source, map, " --map @d/south_lines.geojson"),
           row("--source-region", clone + target + map, source, "--source-region @d/south.geojson"),
           row("--target-region", clone + source + map, target,
               "--target-region 500700,4000000,501100,4000480"),
           row("--snap", clone + target + source + " --map @d/gappy.geojson", "--snap 0.01",
               "--snap 6"),
           row("--method", clone + target + source + map, "--method growth", "--method quilt"),
           row("--method", clone + target + source + map, "--method growth", "--method layout")}),
      batch);
}

}  // namespace
}  // namespace tw::test
