// Where the kernels are found (core/resources.hpp, docs/install.md): the environment variable
// first; for a program of the build tree (this test), the source tree's kernels/. The installed
// program's ../share/terraweave/kernels is tested on an install (tests/scripts/install_test.sh).
#include "core/resources.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

TEST(Resources, KernelsFromTheEnvironmentElseTheSourceTreeForABuildTreeProgram) {
  const char* set = std::getenv("TERRAWEAVE_KERNEL_DIR");
  const bool was_set = set != nullptr;
  const std::string saved = was_set ? set : "";
  ::setenv("TERRAWEAVE_KERNEL_DIR", "/somewhere/kernels", 1);
  EXPECT_EQ(kernel_dir(), fs::path("/somewhere/kernels"));
  ::unsetenv("TERRAWEAVE_KERNEL_DIR");
  EXPECT_EQ(fs::canonical(kernel_dir()), fs::canonical(test::source_dir() / "kernels"));
  EXPECT_TRUE(fs::is_regular_file(kernel_dir() / "row_update.cl"));
  EXPECT_EQ(executable_path().filename(), "test_core");
  if (was_set) ::setenv("TERRAWEAVE_KERNEL_DIR", saved.c_str(), 1);
}

}  // namespace
}  // namespace tw
