// Command line polish (issue #12 item 5): global flags before or after the subcommand, a
// variables file for ${name} (--vars) with errors naming the file and the variable, --seed.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "pipeline/config.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::StartsWith;

const char* const kPipeline = R"(version: 1
seed: ${seed}
generate: { width: 32, height: 32, pixel_size: 10, origin: [500000, 5000000] }
output: { dir: out, preview: false, exr: false }
features:
  roads:
    source: ${map}
    layer: roads
    kind: road
    width: ${road_width}
)";

class CliOptions : public ::testing::Test {
 protected:
  void SetUp() override {
    write_layer(dir / "map.gpkg", "roads", {{"LINESTRING (500020 4999800, 500300 4999750)", 6.0}});
    std::ofstream(dir / "pipeline.yaml") << kPipeline;
    std::ofstream(dir / "vars.yaml") << "seed: 5\nmap: map.gpkg\nroad_width: 9\n";
  }
  CommandResult terraweave(const std::string& args) {
    return run_command("cd '" + dir.path().string() + "' && '" + terraweave_binary().string() +
                       "' " + args);
  }
  nlohmann::json report() { return nlohmann::json::parse(read_file(dir / "out/report.json")); }

  TempDir dir;
};

TEST_F(CliOptions, VariablesFillThePipelineAndSetAndSeedComeAfter) {
  CommandResult r = terraweave("run pipeline.yaml --vars vars.yaml -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(report()["seed"], 5);
  EXPECT_EQ(report()["classes"][0]["features"][0]["width_m"], 9.0);
  EXPECT_EQ(report()["config"]["features"]["roads"]["width"], 9);
  // --set and --seed override what the variables gave.
  r = terraweave("-q run pipeline.yaml --vars vars.yaml --seed 11 --set features.roads.width=4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(report()["seed"], 11);
  EXPECT_EQ(report()["classes"][0]["features"][0]["width_m"], 4.0);
}

TEST_F(CliOptions, AnUnknownOrMissingVariableNamesFileKeyAndVariable) {
  std::ofstream(dir / "short.yaml") << "seed: 5\nmap: map.gpkg\n";
  CommandResult r = terraweave("-q validate pipeline.yaml --vars short.yaml");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(lines_of(r.output),
              ElementsAre("terraweave: error: pipeline.yaml:10:12: features.roads.width: "
                          "${road_width}: not defined in the variables file short.yaml (it "
                          "defines map, seed)"));
  r = terraweave("-q validate pipeline.yaml");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("pipeline.yaml:2:7: seed: ${seed}: no variables file given"));
  std::ofstream(dir / "bad.yaml") << "seed: [1, 2]\n";
  r = terraweave("-q validate pipeline.yaml --vars bad.yaml");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(lines_of(r.output),
              ElementsAre("terraweave: error: bad.yaml:1:1: seed: expected a single value (a "
                          "number or a string)"));
  r = terraweave("-q validate pipeline.yaml --vars none.yaml");
  EXPECT_THAT(r.output, HasSubstr("none.yaml: cannot read the variables file"));
}

// The variables file is bounded as the pipeline file is, before anything is read (issue #24
// item 5: `--vars /dev/zero` was a bad_alloc after 28 s).
TEST_F(CliOptions, AVariablesFileIsARegularFileOfBoundedSize) {
  CommandResult r = terraweave("-q validate pipeline.yaml --vars /dev/zero");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(lines_of(r.output),
              ElementsAre("terraweave: error: /dev/zero: not a regular file; a variables file is "
                          "a YAML file"));
  fs::create_directory(dir / "folder");
  r = terraweave("-q validate pipeline.yaml --vars folder");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(lines_of(r.output),
              ElementsAre("terraweave: error: folder: is a folder; give the variables file (YAML) "
                          "itself"));
  std::ofstream(dir / "big.yaml") << "seed: 5\n";
  fs::resize_file(dir / "big.yaml", kMaxPipelineFileBytes + 1);  // sparse: nothing written
  r = terraweave("-q validate pipeline.yaml --vars big.yaml");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(lines_of(r.output),
              ElementsAre("terraweave: error: big.yaml: over 16 MiB; a variables file is a few KiB "
                          "of YAML"));
}

TEST_F(CliOptions, GlobalFlagsWorkBeforeAndAfterTheSubcommand) {
  for (const std::string args : {"-q --threads 2 run pipeline.yaml --vars vars.yaml",
                                 "run pipeline.yaml --vars vars.yaml --threads 2 -q"}) {
    const CommandResult r = terraweave(args);
    EXPECT_EQ(r.exit_code, 0) << args << ": " << r.output;
    // -q: the table of stages only, no [info] log lines.
    EXPECT_THAT(r.output, Not(HasSubstr("[info]"))) << args;
  }
  for (const std::string args : {"--threads 0 validate pipeline.yaml --vars vars.yaml",
                                 "validate pipeline.yaml --vars vars.yaml --threads 0"}) {
    const CommandResult r = terraweave(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_THAT(lines_of(r.output),
                ElementsAre(StartsWith("terraweave: usage error: --threads: Value 0 not in range "
                                       "1 to 1024")));
  }
  // --strict after the subcommand: the short road's warning fails validation.
  std::ofstream(dir / "short.yaml") << "seed: 5\nmap: short.gpkg\nroad_width: 9\n";
  write_layer(dir / "short.gpkg", "roads", {{"LINESTRING (500020 4999800, 500021 4999800)", 6.0}});
  EXPECT_EQ(terraweave("-q validate pipeline.yaml --vars short.yaml").exit_code, 0);
  EXPECT_EQ(terraweave("-q validate pipeline.yaml --vars short.yaml --strict").exit_code, 1);
  EXPECT_EQ(terraweave("-q --strict validate pipeline.yaml --vars short.yaml").exit_code, 1);
}

}  // namespace
}  // namespace tw::test
