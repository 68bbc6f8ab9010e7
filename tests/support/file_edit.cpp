#include "file_edit.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace tw::test {

void flip_byte_in_place(const std::filesystem::path& path, std::uintmax_t from_end) {
  namespace fs = std::filesystem;
  fs::permissions(path, fs::perms::owner_write, fs::perm_options::add);
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  const auto at = std::streamoff(fs::file_size(path) - from_end);
  file.seekg(at);
  const char byte = char(file.get());
  file.seekp(at);
  file.put(char(byte ^ 0x5a));
  ASSERT_TRUE(file.good()) << "cannot edit " << path;
}

}  // namespace tw::test
