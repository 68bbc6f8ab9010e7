// The program loads OpenImageIO only for a command that reads or writes an image (issue #23
// item 4, src/cli/image_module_loader.cpp): LD_DEBUG=files names every shared object the
// dynamic loader opens.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cache_world.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::string loaded_by(const std::string& arguments) {
  const test::CommandResult result = test::run_command(
      "LD_DEBUG=files " + test::terraweave_binary().string() + " " + arguments + " 2>&1");
  EXPECT_EQ(result.exit_code, 0) << result.output.substr(0, 2000);
  return result.output;
}

TEST(ImageModule, CommandsWithoutImagesDoNotLoadOpenImageIO) {
  const std::string version = loaded_by("--version");
  EXPECT_THAT(version, HasSubstr("OpenImageIO"));  // its version, from the headers
  EXPECT_THAT(version, HasSubstr("libstdc++"));    // the loader's trace is there
  EXPECT_THAT(version, Not(HasSubstr("libOpenImageIO")));
  EXPECT_THAT(version, Not(HasSubstr("libterraweave_image")));
}

TEST(ImageModule, AnExemplarLoadsTheModuleAndReadsThroughIt) {
  test::TempDir dir;
  const std::string exemplar =
      (test::source_dir() / "samples/exemplars/cobble_bed_260x80.png").string();
  const std::string trace =
      loaded_by("exemplar inspect " + exemplar + " --preview " + (dir / "preview.png").string());
  EXPECT_THAT(trace, HasSubstr("libterraweave_image.so"));
  EXPECT_THAT(trace, HasSubstr("libOpenImageIO"));
  EXPECT_THAT(trace, HasSubstr("coverage"));  // the exemplar was read
  // The preview PNG was written through the module: a PNG signature and more.
  const std::string png = test::read_file(dir / "preview.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

// A program copied away from its module still runs what needs no image, and names the module
// (and the variable that points at it) for an image.
TEST(ImageModule, AMissingModuleIsOneClearError) {
  test::TempDir dir;
  const std::filesystem::path program = dir / "terraweave";
  std::filesystem::copy_file(test::terraweave_binary(), program);
  EXPECT_EQ(test::run_command(program.string() + " --version 2>&1").exit_code, 0);
  const std::string exemplar =
      (test::source_dir() / "samples/exemplars/cobble_bed_260x80.png").string();
  const test::CommandResult result =
      test::run_command(program.string() + " exemplar inspect " + exemplar + " 2>&1");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_THAT(result.output, HasSubstr("images need the module libterraweave_image.so"));
  EXPECT_THAT(result.output, HasSubstr("TERRAWEAVE_IMAGE_MODULE"));
  // The variable points at the build's module: the same program reads the exemplar.
  const std::filesystem::path module =
      test::terraweave_binary().parent_path() / "libterraweave_image.so";
  const test::CommandResult pointed =
      test::run_command("TERRAWEAVE_IMAGE_MODULE=" + module.string() + " " + program.string() +
                        " exemplar inspect " + exemplar + " 2>&1");
  EXPECT_EQ(pointed.exit_code, 0) << pointed.output;
  EXPECT_THAT(pointed.output, HasSubstr("coverage"));
}

// Issue #23 item 2: a rerun whose syntheses all come from the cache reads no image. The input
// check remembers a validated exemplar by its bytes (DIR/exemplars/, docs/cache.md) and the
// pattern step reads texels only for a synthesis it runs, so the image module is never loaded.
// A changed or broken exemplar is read and checked again.
class CachedExemplar : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_roads(dir_ / "roads.gpkg", test::roads());
    test::write_exemplar(dir_.path());
    // Tiled without a preview, as the nightly world: a rerun reuses every tile (an untiled
    // run renders again, and the preview PNG is written through the image module).
    std::ofstream(dir_ / "cache.yaml")
        << test::kCachePipeline << "output: { preview: false, tiles: { size: 80, overlap: 2 } }\n";
  }

  // `terraweave run` into `out` (with the cache unless `cached` is false): the loader's trace
  // and the program's messages.
  test::CommandResult run(const std::string& out, bool cached = true) const {
    return test::run_command("LD_DEBUG=files " + test::terraweave_binary().string() + " -q run " +
                             (dir_ / "cache.yaml").string() + " --out " + (dir_ / out).string() +
                             (cached ? " --cache " + (dir_ / "cache").string() : "") + " 2>&1");
  }

  // FID -> the cache status of its synthesis, from report.json.
  std::map<std::int64_t, std::string> whys(const std::string& out) const {
    std::ifstream in(dir_ / out / "report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    std::map<std::int64_t, std::string> by_fid;
    for (const auto& f : report["classes"][0]["features"])
      by_fid[f["fid"]] =
          f["cache"]["status"].get<std::string>() + ": " + f["cache"]["why"].get<std::string>();
    return by_fid;
  }

  void expect_same_outputs(const std::string& a, const std::string& b) const {
    EXPECT_GT(test::expect_same_output_files(dir_ / a, dir_ / b), 5u);
  }

  test::TempDir dir_;
};

TEST_F(CachedExemplar, ACachedRerunLoadsNoImageModuleAndAChangedExemplarIsReadAgain) {
  const test::CommandResult first = run("first");
  ASSERT_EQ(first.exit_code, 0) << first.output.substr(first.output.size() - 2000);
  EXPECT_NE(first.output.find("libterraweave_image.so"), std::string::npos);  // read
  ASSERT_EQ(whys("first").size(), 5u);
  for (const auto& [fid, why] : whys("first")) EXPECT_EQ(why, "rebuilt: new") << fid;

  const test::CommandResult second = run("second");
  ASSERT_EQ(second.exit_code, 0) << second.output.substr(second.output.size() - 2000);
  // The loader's trace is there, and names neither the module nor OpenImageIO.
  EXPECT_NE(second.output.find("libgdal"), std::string::npos);
  EXPECT_EQ(second.output.find("libterraweave_image"), std::string::npos);
  EXPECT_EQ(second.output.find("libOpenImageIO"), std::string::npos);
  for (const auto& [fid, why] : whys("second")) EXPECT_EQ(why, "reused: unchanged") << fid;
  expect_same_outputs("first", "second");

  // Other bytes, the same size: checked, synthesized and rendered anew, as a clean run.
  test::crop_raster(test::source_dir() / "samples/exemplars/cobble_bed_260x80.png",
                    dir_ / "cobble.png", "PNG", 60, 56);
  const test::CommandResult changed = run("changed");
  ASSERT_EQ(changed.exit_code, 0) << changed.output.substr(changed.output.size() - 2000);
  EXPECT_NE(changed.output.find("libterraweave_image.so"), std::string::npos);
  for (const auto& [fid, why] : whys("changed")) EXPECT_EQ(why, "rebuilt: exemplar changed") << fid;
  const test::CommandResult clean = run("clean", false);
  ASSERT_EQ(clean.exit_code, 0) << clean.output.substr(clean.output.size() - 2000);
  expect_same_outputs("changed", "clean");
  const auto before = test::output_files(dir_ / "first"),
             after = test::output_files(dir_ / "changed");
  EXPECT_NE(before, after);  // the new exemplar reached the outputs
}

TEST_F(CachedExemplar, ARememberedExemplarReplacedByABrokenFileFailsAsWithoutACache) {
  ASSERT_EQ(run("first").exit_code, 0);
  std::ofstream(dir_ / "cobble.png", std::ios::trunc) << "not an image\n";
  const test::CommandResult cached = run("cached");
  const test::CommandResult plain = run("plain", false);
  EXPECT_NE(cached.exit_code, 0);
  EXPECT_EQ(cached.exit_code, plain.exit_code);
  // The same one error (the loader's trace lines aside).
  const auto error_lines = [](const std::string& output) {
    std::string lines, line;
    std::istringstream in(output);
    while (std::getline(in, line))
      if (line.find("cobble.png") != std::string::npos && line.find("file=") == std::string::npos)
        lines += line + "\n";
    return lines;
  };
  EXPECT_THAT(error_lines(cached.output), HasSubstr("cannot be used as an exemplar"));
  EXPECT_EQ(error_lines(cached.output), error_lines(plain.output));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "cached"));
}

}  // namespace
}  // namespace tw
