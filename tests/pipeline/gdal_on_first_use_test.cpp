// The program loads GDAL on its first GDAL call (TERRAWEAVE_LAZY_GDAL, src/cli/gdal_loader.hpp,
// docs/performance.md "GDAL on first use"): a generated world's render-tile never loads libgdal
// (LD_DEBUG=files names every shared object the dynamic loader opens), a DEM run loads it and
// writes what it wrote with libgdal loaded at start, and a missing libgdal is one error line
// that leaves nothing behind, even when it comes after the command began staging its outputs.
// Skipped in a build that links GDAL as usual (TW_TEST_LAZY_GDAL: libgdal's file).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cache_world.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

#ifdef TW_TEST_LAZY_GDAL
const char* const kLazyGdalLibrary = TW_TEST_LAZY_GDAL;
#else
const char* const kLazyGdalLibrary = "";
#endif

const char* const kLazyGdalRoads = R"(
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 6 }
)";

class GdalOnFirstUse : public ::testing::Test {
 protected:
  void SetUp() override {
    if (*kLazyGdalLibrary == '\0')
      GTEST_SKIP() << "built with TERRAWEAVE_LAZY_GDAL=OFF: the program links GDAL";
    test::write_layer(dir_ / "map.gpkg", "roads",
                      {{"LINESTRING (500040 5000200, 500440 5000220)", 6.0},
                       {"LINESTRING (500240 5000020, 500250 5000380)", 6.0}});
    std::ofstream(dir_ / "generated.yaml")
        << "version: 1\nseed: 3\n"
           "generate: { width: 48, height: 40, pixel_size: 10, relief: 40, crs: \"EPSG:32631\", "
           "origin: [500000, 5000400] }\n"
           "output: { preview: false, exr: true, geotiff: false, tiles: { size: 24, overlap: 2 "
           "} }"
        << kLazyGdalRoads;
    test::DemSpec dem;  // 48 x 40 cells of 10 m, as the generated world
    dem.width = 48;
    dem.height = 40;
    dem.origin_y = 5000400.0;
    test::write_dem(dir_ / "dem.tif", dem);
    std::ofstream(dir_ / "dem.yaml") << "version: 1\nseed: 3\nheightfield: dem.tif\n"
                                        "output: { preview: false, exr: true, geotiff: true }"
                                     << kLazyGdalRoads;
  }

  // The program in the test's folder: exit code and stdout + stderr (with `env` before it).
  test::CommandResult terraweave(const std::string& args, const std::string& env = "") const {
    return test::run_command("cd '" + dir_.path().string() + "' && " + env + " '" +
                             test::terraweave_binary().string() + "' -q " + args + " 2>&1");
  }

  test::TempDir dir_;
};

// The file `name` somewhere under `root` ("" when none).
std::string lazy_gdal_file_under(const fs::path& root, const std::string& name) {
  for (const auto& entry : fs::recursive_directory_iterator(root))
    if (entry.path().filename() == name) return test::read_file(entry.path());
  return "";
}

// Every file under `root`, relative, sorted (recursive_directory_iterator's order is not). Not
// the folders: render-tile creates the plan's tile folders before it writes (kept for the next
// tiles), which are no temporaries; a staging folder holds files (its .terraweave/lock link).
std::vector<std::string> lazy_gdal_listing(const fs::path& root) {
  std::vector<std::string> paths;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    if (!entry.is_directory())
      paths.push_back(entry.path().lexically_relative(root).generic_string());
  std::sort(paths.begin(), paths.end());
  return paths;
}

TEST_F(GdalOnFirstUse, RenderTileOfAGeneratedWorldLoadsNoGdal) {
  const test::CommandResult plan = terraweave("plan generated.yaml --out out", "LD_DEBUG=files");
  ASSERT_EQ(plan.exit_code, 0) << plan.output.substr(0, 3000);
  EXPECT_THAT(plan.output, HasSubstr("libgdal"));  // the plan reads the roads through OGR
  fs::copy(dir_ / "out", dir_ / "eager", fs::copy_options::recursive);
  const test::CommandResult tile = terraweave("render-tile out --tile 3", "LD_DEBUG=files");
  ASSERT_EQ(tile.exit_code, 0) << tile.output.substr(0, 3000);
  EXPECT_THAT(tile.output, HasSubstr("libstdc++"));  // the loader's trace is there
  EXPECT_THAT(tile.output, Not(HasSubstr("libgdal")));
  EXPECT_THAT(tile.output, Not(HasSubstr("libproj")));
  EXPECT_THAT(tile.output, Not(HasSubstr("libgeos")));
  // The same tile with libgdal loaded at start, as when the program linked it: the same bytes.
  const test::CommandResult eager =
      terraweave("render-tile eager --tile 3", std::string("LD_PRELOAD=") + kLazyGdalLibrary);
  ASSERT_EQ(eager.exit_code, 0) << eager.output;
  const std::string height = lazy_gdal_file_under(dir_ / "out", "height_x1_y1.exr");
  EXPECT_GT(height.size(), 1000u);
  EXPECT_EQ(height, lazy_gdal_file_under(dir_ / "eager", "height_x1_y1.exr"));
}

// A DEM run loads libgdal at its first GDAL call (the loader's "dynamically loaded" line), and
// writes the same bytes as the program with libgdal loaded before main, as it was when linked.
TEST_F(GdalOnFirstUse, ADemRunLoadsGdalOnFirstUseAndWritesTheSameBytes) {
  const test::CommandResult run = terraweave("run dem.yaml --out lazy", "LD_DEBUG=files");
  ASSERT_EQ(run.exit_code, 0) << run.output.substr(0, 3000);
  bool loaded_on_first_use = false;
  for (const std::string& line : test::lines_of(run.output))
    loaded_on_first_use |= line.find("file=libgdal") != std::string::npos &&
                           line.find("dynamically loaded by") != std::string::npos;
  EXPECT_TRUE(loaded_on_first_use) << run.output.substr(0, 3000);
  const test::CommandResult eager =
      terraweave("run dem.yaml --out eager", std::string("LD_PRELOAD=") + kLazyGdalLibrary);
  ASSERT_EQ(eager.exit_code, 0) << eager.output;
  // The GeoTIFF twins, the EXR layers and the features, byte for byte.
  EXPECT_TRUE(fs::exists(dir_ / "lazy/height.tif"));
  EXPECT_GT(test::expect_same_output_files(dir_ / "lazy", dir_ / "eager"), 5u);
}

TEST_F(GdalOnFirstUse, AMissingLibgdalIsOneErrorLine) {
  const std::string missing = "TERRAWEAVE_GDAL_LIBRARY=" + (dir_ / "none/libgdal.so").string();
  // What needs no GDAL still runs, and the variable may name the library.
  EXPECT_EQ(terraweave("--version", missing).exit_code, 0);
  EXPECT_EQ(terraweave("run dem.yaml --out named",
                       std::string("TERRAWEAVE_GDAL_LIBRARY=") + kLazyGdalLibrary)
                .exit_code,
            0);
  const test::CommandResult run = terraweave("run dem.yaml --out out", missing);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, StartsWith("terraweave: error: GDAL is needed here but could not load "));
  EXPECT_THAT(run.output, HasSubstr("none/libgdal.so"));
  EXPECT_THAT(run.output, HasSubstr("TERRAWEAVE_GDAL_LIBRARY"));
  EXPECT_EQ(test::lines_of(run.output).size(), 1u) << run.output;
}

// libgdal fails to load after the command staged files: the error line, exit code 1, and the
// folder as before (lazy_library's _exit skips the stagers' destructors, so it removes their
// temporaries itself). A tile with GeoTIFF twins calls GDAL first for height.tif, after
// height.exr was staged beside its final name; finish first calls it after it staged the
// tiles' files into the output folder's staging folder, beside the folder.
TEST_F(GdalOnFirstUse, AMissingLibgdalAfterStagingBeganLeavesNothingBehind) {
  std::string twins = test::read_file(dir_ / "generated.yaml");
  const std::size_t off = twins.find("geotiff: false");
  ASSERT_NE(off, std::string::npos);
  twins.replace(off, std::string("geotiff: false").size(), "geotiff: true");
  std::ofstream(dir_ / "twins.yaml") << twins;
  const test::CommandResult plan =
      terraweave("plan twins.yaml --out out --set output.tiles.size=48");  // one tile
  ASSERT_EQ(plan.exit_code, 0) << plan.output;
  const std::string missing = "TERRAWEAVE_GDAL_LIBRARY=" + (dir_ / "none/libgdal.so").string();
  const auto expect_missing_gdal_leaves_nothing = [&](const std::string& command) {
    const std::vector<std::string> before = lazy_gdal_listing(dir_.path());
    const test::CommandResult run = terraweave(command, missing);
    EXPECT_EQ(run.exit_code, 1) << command;
    EXPECT_THAT(run.output,
                StartsWith("terraweave: error: GDAL is needed here but could not load "));
    EXPECT_EQ(test::lines_of(run.output).size(), 1u) << run.output;
    EXPECT_EQ(lazy_gdal_listing(dir_.path()), before) << command;
  };
  expect_missing_gdal_leaves_nothing("render-tile out --tile 0");
  const test::CommandResult tile = terraweave("render-tile out --tile 0");
  ASSERT_EQ(tile.exit_code, 0) << tile.output;
  expect_missing_gdal_leaves_nothing("finish out");
  // With libgdal, the finish still completes the run.
  const test::CommandResult finish = terraweave("finish out");
  ASSERT_EQ(finish.exit_code, 0) << finish.output;
  EXPECT_TRUE(fs::exists(dir_ / "out/report.json"));
}

}  // namespace
}  // namespace tw
