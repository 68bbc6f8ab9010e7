#pragma once
// terraweave's version, as in the top CMakeLists.txt project() (keep the two in step).
#include <string>

namespace tw {

inline constexpr const char* kTerraweaveVersion = "0.1.0";

// "terraweave 0.1.0 (GDAL x, yaml-cpp, OpenImageIO y, ...)": one line for --version and reports.
std::string version_line();

}  // namespace tw
