// What remove_registered_staging removes (core/staging_registry.hpp): the files and folders
// that StagedPaths hold, not a released one, and the stagers register their temporaries.
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
  const StagedPath staged_file(file);
  const StagedPath staged_folder(folder);
  StagedPath staged_kept(kept);
  staged_kept.release();  // renamed into place: no longer a temporary
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

TEST(StagedPath, ARemovedOrReleasedPathIsNoLongerRegistered) {
  test::TempDir dir;
  const fs::path file = dir.path() / "file.tmp";
  {
    std::ofstream(file) << "x";
    const StagedPath staged(file);
  }
  EXPECT_FALSE(fs::exists(file));  // the destructor removed it...
  std::ofstream(file) << "x";
  remove_registered_staging();
  EXPECT_TRUE(fs::exists(file));  // ...and unregistered it
  StagedPath released(file);
  released.release();
  EXPECT_TRUE(released.empty());
  remove_registered_staging();
  EXPECT_TRUE(fs::exists(file));
}

TEST(StagedPath, AMovedFromOneNeitherRemovesNorUnregisters) {
  test::TempDir dir;
  const fs::path file = dir.path() / "file.tmp";
  std::ofstream(file) << "x";
  StagedPath moved_to;
  {
    StagedPath original(file);
    moved_to = std::move(original);
  }
  EXPECT_EQ(moved_to.path(), file);
  EXPECT_TRUE(fs::exists(file));
  remove_registered_staging();
  EXPECT_FALSE(fs::exists(file));  // still registered, once
}

TEST(StagedPath, TwoHoldersOfOnePathUnregisterOnceEach) {
  test::TempDir dir;
  const fs::path file = dir.path() / "file.tmp";
  std::ofstream(file) << "x";
  StagedPath first(file);
  const StagedPath second(file);
  first.release();
  remove_registered_staging();
  EXPECT_FALSE(fs::exists(file));  // second still held it
}

TEST(StagedPath, AssigningOverAHeldPathRemovesIt) {
  test::TempDir dir;
  const fs::path old_file = dir.path() / "old.tmp";
  const fs::path new_file = dir.path() / "new.tmp";
  std::ofstream(old_file) << "x";
  std::ofstream(new_file) << "x";
  StagedPath staged(old_file);
  staged = StagedPath(new_file);
  EXPECT_FALSE(fs::exists(old_file));
  EXPECT_TRUE(fs::exists(new_file));
  staged.release();
}

}  // namespace
}  // namespace tw
