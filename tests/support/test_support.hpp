#pragma once
// Helpers shared by every test executable.
#include <filesystem>
#include <string>
#include <vector>

namespace tw::test {

// The repository root (TERRAWEAVE_SOURCE_DIR overrides the build-time default).
std::filesystem::path source_dir();
// The built terraweave executable (TERRAWEAVE_BINARY overrides the build-time default).
std::filesystem::path terraweave_binary();

// A fresh folder removed at the end of the test.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

struct CommandResult {
  int exit_code = 0;
  std::string output;  // stdout and stderr together
};
// Runs a shell command line and captures what it prints.
CommandResult run_command(const std::string& command_line);

// A file's bytes ("" when it cannot be read).
std::string read_file(const std::filesystem::path& path);
// The lines of a text, without their line breaks.
std::vector<std::string> lines_of(const std::string& text);

}  // namespace tw::test
