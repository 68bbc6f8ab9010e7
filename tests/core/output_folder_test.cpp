// OutputFolder's one path check (issue #9 item 8): nothing is staged outside the folder or in
// its .terraweave bookkeeping; what it commits are plain files. The commit itself is tested on
// the real binary (tests/pipeline/output_folder_test.cpp).
#include "core/output_folder.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "core/error.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST(OutputFolder, StagesOnlyInsideTheFolder) {
  test::TempDir dir;
  OutputFolder folder(dir / "out");
  for (const fs::path& outside :
       {dir / "out/placements/../../x.json", dir / "x.json", dir / "out/.terraweave/gen-1/a",
        dir / "out", fs::path("/etc/x"), dir / "out/a/../../out2/b"}) {
    SCOPED_TRACE(outside.string());
    try {
      folder.stage(outside);
      ADD_FAILURE() << "staged";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("is outside the output folder"));
    }
  }
  const fs::path staged = folder.stage(dir / "out/placements/../placements/roads_1.json");
  std::ofstream(staged) << "{}";
  folder.commit();
  ASSERT_EQ(folder.committed().size(), 1u);
  EXPECT_EQ(folder.committed()[0], dir / "out/placements/roads_1.json");
  EXPECT_TRUE(folder.swaps());
  EXPECT_EQ(fs::symlink_status(dir / "out/placements/roads_1.json").type(), fs::file_type::regular);
  EXPECT_EQ(test::read_file(dir / "out/.terraweave/outputs").substr(0, 19), "terraweave outputs ");
  std::ifstream in(dir / "out/placements/roads_1.json");
  std::string text;
  in >> text;
  EXPECT_EQ(text, "{}");
  EXPECT_FALSE(fs::exists(dir / "x.json"));
}

}  // namespace
}  // namespace tw
