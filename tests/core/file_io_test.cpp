// write_file_atomic's failures say why (issue #24: a full disk gave an empty reason); a
// MappedFile holds the bytes read_file_bytes reads.
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

// A mapping of several pages (and a partial last one) holds the file's bytes, moves with them,
// and outlives the file's replacement by rename (write_file_atomic) and its removal.
TEST(FileIo, AMappedFileHoldsTheBytesReadFileBytesReads) {
  test::TempDir dir;
  std::string bytes(3 * 4096 + 123, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = char(i * 7 + i / 4096);
  write_file_atomic(dir / "object.bin", bytes);
  MappedFile mapped(dir / "object.bin");
  EXPECT_EQ(mapped.bytes(), read_file_bytes(dir / "object.bin"));
  EXPECT_EQ(mapped.bytes(), bytes);
  write_file_atomic(dir / "object.bin", "replaced");
  EXPECT_EQ(mapped.bytes(), bytes);  // the old file, still mapped
  fs::remove(dir / "object.bin");
  MappedFile moved(std::move(mapped));
  EXPECT_EQ(moved.bytes(), bytes);
  EXPECT_TRUE(mapped.bytes().empty());  // NOLINT(bugprone-use-after-move): moved from, empty
  write_file_atomic(dir / "empty.bin", "");
  moved = MappedFile(dir / "empty.bin");
  EXPECT_TRUE(moved.bytes().empty());
}

TEST(FileIo, AFileThatCannotBeMappedNamesItAndTheReason) {
  test::TempDir dir;
  for (const fs::path& path : {dir / "missing.bin", dir.path()}) {
    try {
      MappedFile mapped(path);
      ADD_FAILURE() << "mapped " << path;
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(path.string()));
    }
  }
}

}  // namespace
}  // namespace tw
