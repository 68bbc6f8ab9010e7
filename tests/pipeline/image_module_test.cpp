// The program loads OpenImageIO only for a command that reads or writes an image (issue #23
// item 4, src/cli/image_module_loader.cpp): LD_DEBUG=files names every shared object the
// dynamic loader opens.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "test_support.hpp"

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
  EXPECT_THAT(version, HasSubstr("libgdal"));      // the loader's trace is there
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

}  // namespace
}  // namespace tw
