#include "core/resources.hpp"

#include <cstdlib>

namespace tw {

namespace fs = std::filesystem;

fs::path executable_path() {
  std::error_code ec;
  fs::path path = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : path;
}

namespace {

// Whether `path` lies inside `folder` (both absolute and normal).
bool is_inside(const fs::path& path, const fs::path& folder) {
  const fs::path relative = path.lexically_relative(folder);
  return !relative.empty() && *relative.begin() != "..";
}

}  // namespace

fs::path kernel_dir() {
  if (const char* set = std::getenv("TERRAWEAVE_KERNEL_DIR"); set != nullptr && *set != '\0')
    return set;
  const fs::path program = executable_path();
  const fs::path installed =
      (program.parent_path().parent_path() / TERRAWEAVE_DATA_DIR / "kernels").lexically_normal();
  std::error_code ec;
  if (fs::is_directory(installed, ec)) return installed;
  const fs::path build_tree = fs::path(TERRAWEAVE_BUILD_DIR).lexically_normal();
  const fs::path source_kernels = fs::path(TERRAWEAVE_SOURCE_DIR) / "kernels";
  if (is_inside(program.lexically_normal(), build_tree) && fs::is_directory(source_kernels, ec))
    return source_kernels;
  return installed;
}

}  // namespace tw
