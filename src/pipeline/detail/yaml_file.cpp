#include "pipeline/detail/yaml_file.hpp"

#include <array>
#include <fstream>

#include "core/error.hpp"
#include "pipeline/config.hpp"

namespace tw::detail {

namespace fs = std::filesystem;

std::string read_small_yaml_file(const fs::path& file, std::string_view what) {
  // Only a regular file of bounded size: a folder, a device (/dev/zero) or a FIFO would read
  // nothing useful, or forever.
  std::error_code error;
  const fs::file_status status = fs::status(file, error);
  if (!fs::exists(status)) fail("{}: cannot read the {} file: no such file", file.string(), what);
  if (fs::is_directory(status))
    fail("{}: is a folder; give the {} file (YAML) itself", file.string(), what);
  if (!fs::is_regular_file(status))
    fail("{}: not a regular file; a {} file is a YAML file", file.string(), what);
  const auto too_large = [&] {
    fail("{}: over {} MiB; a {} file is a few KiB of YAML", file.string(),
         kMaxPipelineFileBytes >> 20, what);
  };
  if (fs::file_size(file, error) > kMaxPipelineFileBytes) too_large();
  std::ifstream in(file, std::ios::binary);
  if (!in) fail("{}: cannot read the {} file", file.string(), what);
  std::string text;
  std::array<char, 65536> chunk;
  while (in.read(chunk.data(), chunk.size()) || in.gcount() > 0) {  // bounded, should it grow
    text.append(chunk.data(), std::size_t(in.gcount()));
    if (text.size() > kMaxPipelineFileBytes) too_large();
  }
  if (in.bad()) fail("{}: cannot read the {} file", file.string(), what);
  return text;
}

}  // namespace tw::detail
