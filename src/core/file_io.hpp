#pragma once
// Whole small files as bytes. write_file_atomic writes a temporary beside the file (its name
// holds the host and pid, so processes on machines sharing a folder never share one) and
// renames it over `path`: a reader sees the old file or the new one, and a writer killed on the
// way leaves only its temporary.
#include <filesystem>
#include <string>
#include <string_view>

namespace tw {

// Throws tw::Error naming the file when it cannot be read.
std::string read_file_bytes(const std::filesystem::path& path);

// A whole file's bytes mapped read-only: the page cache's own pages, with neither a buffer to
// fault in and fill nor a copy (a render-tile's plan objects, ~8 MB read per process). For
// files replaced by rename, never rewritten in place (write_file_atomic's): a file truncated
// while mapped would fault its reader. Throws tw::Error naming the file when it cannot be read.
class MappedFile {
 public:
  explicit MappedFile(const std::filesystem::path& path);
  ~MappedFile();
  MappedFile(MappedFile&& other) noexcept;
  MappedFile& operator=(MappedFile&& other) noexcept;
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::string_view bytes() const { return {data_, size_}; }

 private:
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};
// Creates the folder. Throws tw::Error naming the file when it cannot be written.
void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);
// A name for a temporary beside `path`: .<stem>.tmp-<host>-<pid><ext> (same extension, for
// writers that look at it).
std::filesystem::path temporary_beside(const std::filesystem::path& path);

}  // namespace tw
