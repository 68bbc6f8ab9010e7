// write_file_atomic's failures say why (issue #24: a full disk gave an empty reason).
#include "core/file_io.hpp"

#include <sys/resource.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <csignal>
#include <string>

#include "core/error.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// A file-size limit fails write(2) with EFBIG as a full disk fails it with ENOSPC, without a
// file system to fill; the limit and SIGXFSZ's handler are put back on the way out.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*handler_)(int) = SIG_DFL;
};

TEST(FileIo, AWriteThatDoesNotFitNamesTheFileAndTheReasonAndLeavesTheOldOne) {
  test::TempDir dir;
  const fs::path file = dir / "plan.json";
  write_file_atomic(file, "old");
  std::string message;
  {
    FileSizeLimit limit(4096);
    try {
      write_file_atomic(file, std::string(100000, 'x'));
    } catch (const Error& e) {
      message = e.what();
    }
  }
  EXPECT_THAT(message, HasSubstr("cannot write " + file.string() + ": File too large"));
  EXPECT_EQ(read_file_bytes(file), "old");
  // Nothing but the old file: the temporary is gone.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

TEST(FileIo, AFolderThatCannotBeMadeNamesItAndTheReason) {
  test::TempDir dir;
  write_file_atomic(dir / "blocker", "b");  // a file where the folder should be
  try {
    write_file_atomic(dir / "blocker/x.json", "x");
    ADD_FAILURE() << "written";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot create " + (dir / "blocker").string() + ": "));
    EXPECT_GT(std::string(e.what()).size(),
              ("cannot create " + (dir / "blocker").string() + ": ").size());
  }
}

}  // namespace
}  // namespace tw
