#pragma once
// Where terraweave's read-only files are (kernels/*.cl; docs/install.md): found relative to
// the program, so that an installed tree works wherever it is copied or moved.
//   1. the environment variable TERRAWEAVE_KERNEL_DIR, when set;
//   2. <program's folder>/../share/terraweave/kernels (an installed program: bin/terraweave);
//   3. for a program of the build tree only (the CLI, tests, benchmarks): the source tree's
//      kernels/. An installed program never looks there.
#include <filesystem>

namespace tw {

// The running program's path (/proc/self/exe); empty when it cannot be read.
std::filesystem::path executable_path();

// The folder of the OpenCL kernels, by the rules above. When none exists, the installed
// location (2.), so that an error names where they were looked for.
std::filesystem::path kernel_dir();

}  // namespace tw
