// What remove_registered_staging removes (core/staging_registry.hpp): the registered files and
// folders, not an unregistered one, and the stagers register their temporaries.
#include "core/staging_registry.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "core/atomic_output.hpp"
#include "core/output_folder.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

TEST(StagingRegistry, RemovesTheRegisteredPathsOnly) {
  test::TempDir dir;
  const fs::path file = dir.path() / "file.tmp";
  const fs::path folder = dir.path() / "folder";
  const fs::path kept = dir.path() / "kept.tmp";
  std::ofstream(file) << "x";
  fs::create_directories(folder / "inner");
  std::ofstream(folder / "inner/a") << "x";
  std::ofstream(kept) << "x";
  register_staging(file);
  register_staging(folder);
  register_staging(kept);
  unregister_staging(kept);  // renamed into place: no longer a temporary
  remove_registered_staging();
  EXPECT_FALSE(fs::exists(file));
  EXPECT_FALSE(fs::exists(folder));
  EXPECT_TRUE(fs::exists(kept));
}

TEST(StagingRegistry, TheStagersRegisterTheirTemporariesUntilCommitted) {
  test::TempDir dir;
  OutputTransaction transaction;
  const fs::path temporary = transaction.stage(dir.path() / "a.txt");
  std::ofstream(temporary) << "a";
  OutputFolder folder(dir.path() / "out");
  std::ofstream(folder.stage(dir.path() / "out/b.txt")) << "b";
  remove_registered_staging();  // as a failed library load does before _exit
  EXPECT_FALSE(fs::exists(temporary));
  EXPECT_EQ(folder.staged_files().size(), 1u);
  EXPECT_FALSE(fs::exists(folder.staged_files()[0].second));
  // A committed output is no longer registered: nothing to remove.
  OutputTransaction second;
  std::ofstream(second.stage(dir.path() / "c.txt")) << "c";
  second.commit();
  remove_registered_staging();
  EXPECT_TRUE(fs::exists(dir.path() / "c.txt"));
}

}  // namespace
}  // namespace tw
