#pragma once
// Reading a small YAML file (a pipeline, a --vars file) with its size bounded before anything
// is allocated for it.
#include <filesystem>
#include <string>
#include <string_view>

namespace tw::detail {

// The bytes of `file`, which must be a regular file of at most kMaxPipelineFileBytes
// (pipeline/config.hpp): a folder, a device (/dev/zero), a FIFO or a larger file fails at once
// with one line naming the file and what it should be, reading never more than the bound plus
// one block. `what` is "pipeline" or "variables".
std::string read_small_yaml_file(const std::filesystem::path& file, std::string_view what);

}  // namespace tw::detail
