// No command writes over what it reads or into a run's folder (issue #24 item 1, core/
// output_guard.hpp): `export out --to unreal --out out` deleted the run it exported, `area` and
// `grow --out RUN` replaced its files, `view RUN --out RUN/height.tif` replaced a layer with HTML.
// Each case through the real CLI: exit 1, one line naming the option and what to do, and the
// run's files byte for byte as they were.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include "test_support.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// Every regular file under `dir` (outside .terraweave) with its bytes.
std::map<std::string, std::string> files_of(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator();
       ++it) {
    if (it->path().filename() == ".terraweave") {
      it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file())
      files[it->path().lexically_relative(dir).string()] = read_file(it->path());
  }
  return files;
}

class OutputGuard : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir / "pipeline.yaml") << R"(version: 1
seed: 3
generate: { width: 48, height: 40, pixel_size: 10, relief: 40, origin: [500000, 5000000] }
output: { preview: false, exr: false }
features:
  ridges: { source: )" << (source_dir() / "samples/map.gpkg").string()
                                         << R"(, layer: ridges, kind: ridge, width: 20 }
)";
    ASSERT_EQ(terraweave("-q run pipeline.yaml --out run").exit_code, 0);
    ASSERT_EQ(terraweave("-q run pipeline.yaml --out other").exit_code, 0);
    before = files_of(dir / "run");
    ASSERT_TRUE(before.contains("height.tif"));
  }
  CommandResult terraweave(const std::string& args) const {
    return run_command("cd '" + dir.path().string() + "' && '" + terraweave_binary().string() +
                       "' " + args + " 2>&1");
  }
  void expect_refused(const std::string& args, const std::string& why) {
    const CommandResult r = terraweave(args);
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr("terraweave: error: ")) << args;
    EXPECT_THAT(r.output, HasSubstr(why)) << args;
    EXPECT_THAT(r.output, HasSubstr("of its own")) << args;  // what to do
    EXPECT_EQ(files_of(dir / "run"), before) << args << " changed the run";
  }
  TempDir dir;
  std::map<std::string, std::string> before;
};

TEST_F(OutputGuard, NoCommandWritesOverItsInputOrARunsFolder) {
  const std::string samples = (source_dir() / "samples").string();
  expect_refused("export run --to unreal --out run", "export --out run: is what export reads");
  expect_refused("export run --to unreal --out ./run/", "is what export reads");  // spelled else
  expect_refused("export run --to unreal --out run/engine", "lies inside what export reads");
  expect_refused("export run --to unreal --out other", "is the output folder of a run");
  expect_refused("area " + samples + "/sketches/vineyard.geojson --polygons " + samples +
                     "/map.gpkg:existing --out run",
                 "area --out run: is the output folder of a run");
  expect_refused("grow --dem " + samples + "/dem.tif --region 290000,9112000,291000,9113000 " +
                     "--element " + samples + "/ornaments/hedge.json --out run",
                 "grow --out run: is the output folder of a run");
  expect_refused("view run --out run/height.tif", "view --out run/height.tif: lies inside");
  EXPECT_EQ(files_of(dir / "other").size(), before.size());  // the other run is whole too

  // What the commands are for still works: an export of its own, written again, and view's
  // page in the run folder (its documented default).
  EXPECT_EQ(terraweave("-q export run --to unreal --out run-unreal").exit_code, 0);
  EXPECT_EQ(terraweave("-q export run --to unreal --out run-unreal").exit_code, 0);
  EXPECT_EQ(terraweave("view run").exit_code, 0);
  auto with_page = before;
  with_page["view.html"] = read_file(dir / "run/view.html");
  EXPECT_EQ(files_of(dir / "run"), with_page);
}

}  // namespace
}  // namespace tw::test
