// The command line on hostile or careless input (issue #9 items 3, 5, 6): one line per error
// whatever the input holds, range messages that name the range, and synth going through the
// pipeline's checks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "test_support.hpp"
#include "test_world.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

const char* const kPipeline = R"(version: 1
seed: 1
heightfield: dem.tif
output: { dir: out, preview: false }
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 6 }
)";

class CliHardening : public ::testing::Test {
 protected:
  void SetUp() override {
    write_dem(dir / "dem.tif");
    write_layer(dir / "map.gpkg", "roads",
                {{"LINESTRING (500100 5000100, 500300 5000300, 500500 5000350)", 6.0},
                 {"LINESTRING (500100 5000500, 500102 5000500)", 6.0}});  // 2 m: under delta
    std::ofstream(dir / "pipeline.yaml") << kPipeline;
  }

  // `args` may use the shell's printf to put a newline in an argument.
  CommandResult terraweave(const std::string& args) {
    return run_command("cd '" + dir.path().string() + "' && '" + terraweave_binary().string() +
                       "' " + args);
  }

  TempDir dir;
};

TEST_F(CliHardening, ANewlineInAValueOrKeyStaysOnTheErrorLine) {
  for (const std::string set :
       {"\"$(printf 'seed=x\\nterraweave: ok')\"", "\"$(printf 'bad\\nterraweave: ok=1')\""}) {
    const CommandResult r = terraweave("-q validate pipeline.yaml --set " + set);
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_THAT(lines_of(r.output), ElementsAre(StartsWith("terraweave: error: --set ")));
    EXPECT_THAT(r.output, HasSubstr("\\nterraweave: ok"));
  }
  // A usage error holding a newline is one line too.
  const CommandResult usage = terraweave("-q run pipeline.yaml --threads \"$(printf '1\\n2')\"");
  EXPECT_EQ(usage.exit_code, 2);
  EXPECT_THAT(lines_of(usage.output), ElementsAre(StartsWith("terraweave: usage error: ")));
}

TEST_F(CliHardening, ThreadsAreCappedWithAFriendlyRange) {
  for (const std::string threads : {"100000", "0"}) {
    const CommandResult r = terraweave("-q run pipeline.yaml --threads " + threads);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_THAT(r.output, HasSubstr("--threads: Value " + threads + " not in range 1 to 1024"));
    EXPECT_THAT(r.output, Not(HasSubstr("e+308")));
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST_F(CliHardening, AnEmptyOutIsAUsageError) {
  const CommandResult r = terraweave("-q run pipeline.yaml --out ''");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("empty path"));
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST_F(CliHardening, AFeatureShorterThanDeltaIsAWarningNamingItsFid) {
  const CommandResult r = terraweave("-q validate --strict pipeline.yaml");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("features.roads: FID 2: 2.00 m long, shorter than one piece "
                                  "(delta 4 m): it gets no ribbon"));
  const CommandResult relaxed = terraweave("-q validate pipeline.yaml");
  EXPECT_EQ(relaxed.exit_code, 0) << relaxed.output;
  EXPECT_THAT(relaxed.output, HasSubstr("1 warnings"));
}

TEST_F(CliHardening, APipelineFolderIsNamedAsAFolder) {
  const CommandResult r = terraweave("-q validate .");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(lines_of(r.output),
              ElementsAre("terraweave: error: .: is a folder; give the pipeline file (YAML) "
                          "itself"));
}

TEST_F(CliHardening, SynthChecksTheCurvesCoordinatesAndTheCanvasSize) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  write_layer(dir / "nan.gpkg", "lines",
              {{{{500100, 5000100}, {nan, 5000200}, {500300, 5000300}}, 6.0}});
  const std::string exemplar = (source_dir() / "samples/exemplars/chain_199x82.png").string();
  const std::string common = "-q synth --exemplar " + exemplar + " --delta 3 --scale 4 -o s.png";
  CommandResult r = terraweave(common + " --width 4 --curve nan.gpkg");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(lines_of(r.output),
              ElementsAre(HasSubstr("nan.gpkg:lines: FID 1: vertex 1 has a non-finite")));
  r = terraweave(common + " --width 1e9 --curve line --length 12");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("synth: a canvas of 8e+09 x 8e+09 pixels is too large"));
  EXPECT_FALSE(fs::exists(dir / "s.png"));
}

}  // namespace
}  // namespace tw::test
