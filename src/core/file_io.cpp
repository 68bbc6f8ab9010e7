#include "core/file_io.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <system_error>
#include <utility>

#include "core/error.hpp"

namespace tw {

namespace fs = std::filesystem;

std::string read_file_bytes(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) fail("{}: a folder, not a file", path.string());
  // POSIX reads into a buffer of the file's size (a character-by-character istreambuf_iterator
  // copy was most of the time a render-tile spent reading its plan's objects).
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail("cannot read {}: {}", path.string(), std::strerror(errno));
  struct stat st {};
  std::string bytes;
  if (::fstat(fd, &st) == 0 && st.st_size > 0) bytes.resize(std::size_t(st.st_size));
  std::size_t done = 0;
  int error = 0;
  for (;;) {
    if (done == bytes.size()) bytes.resize(std::max<std::size_t>(2 * bytes.size(), 65536));
    const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) error = errno;
    if (n <= 0) break;
    done += std::size_t(n);
  }
  ::close(fd);
  if (error != 0) fail("cannot read {}: {}", path.string(), std::strerror(error));
  bytes.resize(done);
  return bytes;
}

MappedFile::MappedFile(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) fail("{}: a folder, not a file", path.string());
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail("cannot read {}: {}", path.string(), std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int error = errno;
    ::close(fd);
    fail("cannot read {}: {}", path.string(), std::strerror(error));
  }
  if (st.st_size > 0) {  // mmap refuses a length of 0: an empty file is an empty view
    // MAP_POPULATE maps every page in the one call instead of one fault per 16 pages.
    void* data =
        ::mmap(nullptr, std::size_t(st.st_size), PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
    if (data == MAP_FAILED) {
      const int error = errno;
      ::close(fd);
      fail("cannot read {}: {}", path.string(), std::strerror(error));
    }
    data_ = static_cast<const char*>(data);
    size_ = std::size_t(st.st_size);
  }
  ::close(fd);  // the mapping keeps the file
}

MappedFile::~MappedFile() {
  if (data_) ::munmap(const_cast<char*>(data_), size_);
}

MappedFile::MappedFile(MappedFile&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)) {}

MappedFile& MappedFile::operator=(MappedFile&& other) noexcept {
  if (this != &other) {
    if (data_) ::munmap(const_cast<char*>(data_), size_);
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
  }
  return *this;
}

fs::path temporary_beside(const fs::path& path) {
  char host[256] = "host";
  ::gethostname(host, sizeof host - 1);
  host[sizeof host - 1] = '\0';
  return path.parent_path() / fmt::format(".{}.tmp-{}-{}{}", path.stem().string(), host, ::getpid(),
                                          path.extension().string());
}

void write_file_atomic(const fs::path& path, std::string_view bytes) {
  std::error_code ec;
  if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);
  if (ec) fail("cannot create {}: {}", path.parent_path().string(), ec.message());
  const fs::path temporary = temporary_beside(path);
  // POSIX calls rather than a stream: a full disk or a file-size limit must reach the message
  // as its errno ("No space left on device"), which a stream's failbit loses.
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot write {}: {}", path.string(), std::strerror(errno));
  int error = 0;
  for (std::size_t done = 0; done < bytes.size() && error == 0;) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno != EINTR) error = errno;
    if (n > 0) done += std::size_t(n);
  }
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) {
    fs::remove(temporary, ec);
    fail("cannot write {}: {}", path.string(), std::strerror(error));
  }
  fs::rename(temporary, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    fail("cannot write {}: {}", path.string(), ec.message());
  }
}

}  // namespace tw
