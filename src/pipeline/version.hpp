#pragma once
// terraweave's version, as in the top CMakeLists.txt project() (keep the two in step).
#include <map>
#include <string>

namespace tw {

inline constexpr const char* kTerraweaveVersion = "0.1.0";

// "terraweave 0.1.0 (GDAL x, yaml-cpp, OpenImageIO y, ...)": one line for --version and reports.
std::string version_line();

// The libraries a run's outputs depend on, by name (gdal, proj, geographiclib, openimageio,
// openexr): their versions as linked, for report.json.
std::map<std::string, std::string> library_versions();

}  // namespace tw
