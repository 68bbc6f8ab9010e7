#include "core/file_io.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>

#include "core/error.hpp"

namespace tw {

namespace fs = std::filesystem;

std::string read_file_bytes(const fs::path& path) {
  std::error_code ec;
  // A folder opens as a stream on Linux and then throws libstdc++'s "basic_filebuf::underflow".
  if (fs::is_directory(path, ec)) fail("{}: a folder, not a file", path.string());
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("cannot read {}", path.string());
  try {
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) fail("cannot read {}", path.string());
    return bytes;
  } catch (const std::ios_base::failure& e) {
    fail("cannot read {}: {}", path.string(), e.what());
  }
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
